// Fresnel reflectance at a smooth interface, unpolarized (the mean of the s and p
// polarizations), for light arriving at cos_i > 0 from the outside.
#pragma once

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// A dielectric of relative index of refraction eta = n_inside / n_outside; 1 under total
// internal reflection (eta < 1 past the critical angle).
float fresnel_dielectric(float cos_i, float eta);

// A conductor of relative complex index of refraction eta + i k, per channel: the exact
// unpolarized reflectance (Born & Wolf, Principles of Optics, §14.2), in float through the
// complex square root of n^2 - sin^2 (conductor-inl.h, the lane formula both engines run). At
// normal incidence ((eta - 1)^2 + k^2) / ((eta + 1)^2 + k^2); with k = 0 it is
// fresnel_dielectric.
Color fresnel_conductor(float cos_i, Color eta, Color k);

// Schlick's weight (1 - cos_theta)^5, cos_theta clamped to [0, 1]: the lane formula's
// (metal-inl.h Schlick, F0 = 0).
float schlick_weight(float cos_theta);

// Snell's law about a microfacet normal m on o's side (o.m > 0), eta the index of the side i
// enters over o's: i = -o / eta + ((o.m) / eta - cos_t) m, normalized. False under total
// internal reflection.
bool refract(Vec3 o, Vec3 m, float eta, Vec3* i);

}  // namespace wavetrace
