// What a light that is not a shape sends: the radiant intensity of a point, spot or projector
// towards a direction, and the power light selection gives each kind (shading/lights.h samples
// them).
#pragma once

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/light.h"

namespace wavetrace {

struct Scene;

// Radiant intensity (W sr^-1 per channel) of a point, spot or projector light along unit d,
// leaving it: a point's `intensity`; a spot's times its falloff (1 within the falloff start, 0
// beyond the cutoff, between them linear in the angle, Mitsuba 3, or smoothstep in the cosine,
// pbrt-v4) and its texture; a projector's pi `intensity` texture / cos^3 inside its frustum.
Color delta_light_intensity(const Scene& scene, const Light& l, Vec3 d);

// The power light selection gives a light that is not a shape (luminances): a point 4 pi I, a
// spot 2 pi I ((1 - cos start) + (cos start - cos cutoff) / 2), a projector pi I times its
// texture's mean over the frustum's cross-section at unit distance, 4 half_width half_height
// (the integral of I cos^3 over that plane), a directional light the irradiance over a disk of
// the scene's radius, pi r^2 E.
float delta_light_power(const Scene& scene, const Light& l, float scene_radius);

}  // namespace wavetrace
