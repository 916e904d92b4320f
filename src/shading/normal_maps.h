// Normal and bump maps: the shading normal a material's maps give a surface point, in both
// engines (surface_vertex). The tangent frame is the hit's dp/du and dp/dv
// (scene/hit_geometry.h) made orthonormal about the interpolated shading normal n:
//   T = normalize(dp/du - (n . dp/du) n),  B = +-(n x T), the sign that of dp/dv . (n x T),
// so that B follows increasing v also where a mesh's uvs are mirrored (glTF's tangent w).
//
// - Normal map (Mitsuba 3's `normalmap`, glTF's normalTexture, OpenGL's convention: +y green
//   along +v): the texture's linear rgb in [0, 1] as a tangent-space normal 2 rgb - 1, so the
//   new normal is normalize(x T + y B + z n). The image must be read raw (not sRGB-decoded).
// - Bump map (Mitsuba 3's `bumpmap`, pbrt-v4's displacement): heights h(u, v) (the texture's
//   luminance) times bump_scale displace the surface along n; with the derivatives of h by
//   central differences 1/2048 apart in uv, dp'/du = T_u + (dh/du) n and dp'/dv = T_v +
//   (dh/dv) n, T_u, T_v the parts of dp/du, dp/dv in the tangent plane, and the new normal is
//   normalize(dp'/du x dp'/dv) (Mitsuba's BumpMap, without pbrt's h dn/du term).
// Both: a bump map first, then a normal map in the bumped frame; the result turned to the side
// of the geometric normal, and the unperturbed normal kept where the frame is degenerate
// (no dp/du, a zero map normal).
//
// Two corrections, each a material's switch (Material::flip_invalid_normals, bump_shadowing),
// as Mitsuba 3's `normalmap` and `bumpmap` make them by default:
// - A mapped normal n that faces away from the viewer (wo on the other side of n than of the
//   unperturbed normal n0) shades nothing from there; it is mirrored about n0, 2 (n . n0) n0 - n
//   (Schuessler et al. 2017 flip such normals to keep the surface reflecting).
// - Where a bent normal meets light at grazing angles, the smooth surface would be lit to the
//   geometric terminator while the bumps it stands for would shadow one another (the "bump
//   terminator" problem). Estevez et al., "A Microfacet-Based Shadowing Function to Solve the
//   Bump Terminator Problem" (Ray Tracing Gems, 2019) read n as the mean normal of a GGX
//   microsurface over n0 of roughness alpha^2 = min(tan^2 theta_n / 8, 1), theta_n the angle
//   between n and n0, and scale the BSDF towards a direction wi by that surface's Smith
//   masking, G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta_i)), theta_i the angle of wi to n0;
//   the sampling density is left as it was. A direction on different sides of n and n0 gets
//   nothing, as in Mitsuba.
#pragma once

#include <algorithm>
#include <cmath>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/material.h"
#include "wavetrace/shading/surface.h"

namespace wavetrace {

struct Scene;

// The shading normal at the hit, seen from direction wo (unit, away from the surface).
Normal3 mapped_normal(const Scene& scene, const Material& m, const SurfaceHit& hit, Vec3 wo);

// Estevez et al.'s alpha^2 for a mapped normal n over the unperturbed normal n0 (both unit).
inline float bump_shadowing_alpha2(Normal3 n0, Normal3 n) {
    const float c = dot(n, n0);
    const float c2 = c * c;
    if (c2 <= 0.0f) return 1.0f;
    return std::min(0.125f * std::max(1.0f - c2, 0.0f) / c2, 1.0f);
}

// The factor on the BSDF towards wi (unit) at a vertex of mapped normal n over n0 whose
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
