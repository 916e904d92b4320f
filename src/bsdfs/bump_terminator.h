// Estevez et al., "A Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem"
// (Ray Tracing Gems, 2019). Where a bump or normal map bends the shading normal, a smooth
// surface would be lit up to the geometric terminator while the bumps it stands for would
// shadow one another. They read the bent normal n as the mean normal of a GGX microsurface over
// the unperturbed normal n0 of alpha^2 = min(tan^2 theta_n / 8, 1), theta_n the angle between
// n and n0, and scale the BSDF towards a direction wi by that surface's Smith masking,
// G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta_i)), theta_i the angle of wi to n0; the sampling
// density is left as it was. A direction on different sides of n and n0 gets nothing, as in
// Mitsuba 3 (its `normalmap` and `bumpmap`, use_shadowing_function).
#pragma once

#include <algorithm>
#include <cmath>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// alpha^2 for a bent normal n over the unperturbed normal n0 (both unit).
inline float bump_shadowing_alpha2(Normal3 n0, Normal3 n) {
    const float c = dot(n, n0);
    const float c2 = c * c;
    if (c2 <= 0.0f) return 1.0f;
    return std::min(0.125f * std::max(1.0f - c2, 0.0f) / c2, 1.0f);
}

// The factor on the BSDF towards wi (unit) at a vertex of bent normal n over n0 whose
// shadowing has roughness alpha2 (bump_shadowing_alpha2); 1 where alpha2 is 0 (no shadowing).
inline float bump_shadowing(Normal3 n0, Normal3 n, float alpha2, Vec3 wi) {
    if (alpha2 <= 0.0f) return 1.0f;
    const float c = dot(wi, n0);
    if (c * dot(wi, n) <= 0.0f) return 0.0f;
    const float c2 = c * c;
    const float tan2 = std::max(1.0f - c2, 0.0f) / c2;
    return 2.0f / (1.0f + std::sqrt(1.0f + alpha2 * tan2));
}

}  // namespace wavetrace
