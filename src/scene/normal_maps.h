// Normal and bump maps: the shading normal a material's maps give a surface point, in both
// engines (shading's surface_vertex). The tangent frame is the hit's dp/du and dp/dv
// (scene/hit_geometry.h) made orthonormal about the interpolated shading normal n:
//   T = normalize(dp/du - (n . dp/du) n),  B = +-(n x T), the sign that of dp/dv . (n x T),
// so that B follows increasing v also where a mesh's uvs are mirrored (glTF's tangent w).
//
// - Normal map (Mitsuba 3's `normalmap`, glTF's normalTexture, OpenGL's convention: +y green
//   along +v): the texture's linear rgb in [0, 1] as a tangent-space normal 2 rgb - 1, so the
//   new normal is normalize(x T + y B + z n). The image must be read raw (not sRGB-decoded).
// - Bump map (Mitsuba 3's `bumpmap`, pbrt-v4's displacement): heights h(u, v) (the texture's
//   luminance) times bump_scale displace the surface along n; with the derivatives of h (an
//   image's exact ones inside its texel cell, texture_luminance_gradient; other textures' by
//   central differences 1/2048 apart in uv), dp'/du = T_u + (dh/du) n and dp'/dv = T_v +
//   (dh/dv) n, T_u, T_v the parts of dp/du, dp/dv in the tangent plane, and the new normal is
//   normalize(dp'/du x dp'/dv) (Mitsuba's BumpMap, without pbrt's h dn/du term).
// Both: a bump map first, then a normal map in the bumped frame; the result turned to the side
// of the geometric normal, and the unperturbed normal kept where the frame is degenerate
// (no dp/du, a zero map normal).
//
// Two corrections, each a material's switch (Material::flip_invalid_normals, bump_shadowing),
// as Mitsuba 3's `normalmap` and `bumpmap` make them by default: a mapped normal n that faces
// away from the viewer (wo on the other side of n than of the unperturbed normal n0) is
// mirrored about n0, 2 (n . n0) n0 - n (Schuessler et al. 2017 flip such normals to keep the
// surface reflecting); and the BSDF is scaled by Estevez et al.'s bump-terminator shadowing
// (bsdfs/bump_terminator.h).
//
// glTF's clearcoat (KHR_materials_clearcoat) has a normal of its own: its clearcoatNormalTexture
// as a normal map in the same tangent frame over the unperturbed n, or, without one, n itself
// ("no normal mapping is applied to the clear coat layer, even if normal mapping is applied to
// the base material"), turned to the side of the geometric normal as above.
#pragma once

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/material.h"

namespace wavetrace {

struct Scene;

// What the maps read of a surface point: where it is, its geometric normal and interpolated
// shading normal (unit, on the same side), texture coordinates, and dp/du, dp/dv.
struct MappedPoint {
    Point3 p;
    Normal3 ng, ns;
    Vec2 uv;
    Vec3 dpdu, dpdv;
};

// The shading normal at the point, seen from direction wo (unit, away from the surface).
Normal3 mapped_normal(const Scene& scene, const Material& m, const MappedPoint& at, Vec3 wo);

// A metallic-roughness material's clearcoat normal at the point.
Normal3 coat_normal(const Scene& scene, const Material& m, const MappedPoint& at);

}  // namespace wavetrace
