// Warps from [0,1)^2 to directions and points, each with the density it produces. Directions
// are in a local frame with z up unless said otherwise.
#pragma once

#include <algorithm>
#include <cmath>

#include "sampling/warp-inl.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Cosine-weighted hemisphere by Malley's method: a uniform disk point lifted to the
// hemisphere. pdf = cos(theta) / pi. (The one-lane instance of CosineHemisphere.)
inline Vec3 sample_cosine_hemisphere(float u1, float u2) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::to_vec3(lanes::CosineHemisphere<lanes::OneLane>(u1, u2));
}
inline float cosine_hemisphere_pdf(float cos_theta) {
    return std::max(0.0f, cos_theta) * kInvPi;
}

// Uniform on the unit sphere (Archimedes: z uniform in [-1, 1]). pdf = 1 / (4 pi). (The
// one-lane instance of UniformSphere.)
inline Vec3 sample_uniform_sphere(float u1, float u2) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::to_vec3(lanes::UniformSphere<lanes::OneLane>(u1, u2));
}
inline constexpr float uniform_sphere_pdf() {
    return 0.25f * kInvPi;
}

// Uniform in the cone of directions within theta_max of +z. pdf = 1 / (2 pi (1 - cos_max)).
inline Vec3 sample_uniform_cone(float u1, float u2, float cos_max) {
    float cos_theta = 1.0f - u1 * (1.0f - cos_max);
    float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    float phi = 2.0f * kPi * u2;
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}
inline float uniform_cone_pdf(float cos_max) {
    return 1.0f / (2.0f * kPi * (1.0f - cos_max));
}

// The density per unit solid angle of a point drawn uniformly on a surface of area `area`,
// distance^2 = dist2 away, seen at |cos theta| = cos_l. (The one-lane instance of
// UniformAreaToSolidAngle.)
inline float uniform_area_to_solid_angle(float dist2, float cos_l, float area) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::UniformAreaToSolidAngle<lanes::OneLane>(dist2, cos_l, area);
}

// Uniform barycentrics (b1, b2) on a triangle (the square-root warp). pdf = 1 / area.
inline void sample_uniform_triangle(float u1, float u2, float* b1, float* b2) {
    float s = std::sqrt(u1);
    *b1 = s * (1.0f - u2);
    *b2 = s * u2;
}

}  // namespace wavetrace
