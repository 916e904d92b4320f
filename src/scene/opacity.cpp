#include "scene/opacity.h"

#include <algorithm>
#include <bit>
#include <cstdint>

#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {
namespace {

// A 64-bit finaliser (Stafford's Mix13, as in splitmix64): every input bit reaches every
// output bit.
uint64_t mix(uint64_t x) {
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A uniform number in [0, 1) from the ray and the primitive.
float hash_float(const Ray& ray, PrimRef prim) {
    uint64_t h = mix(0x9e3779b97f4a7c15ull ^ prim.bits);
    for (float f : {ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z})
        h = mix(h ^ std::bit_cast<uint32_t>(f));
    return float(h >> 40) * 0x1p-24f;
}

}  // namespace

bool has_alpha_masks(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.opacity != kNone; });
}

Vec2 hit_uv(const Scene& scene, PrimRef prim, float u, float v, Point3 p) {
    switch (prim.kind()) {
        case PrimKind::Triangle: {
            const Triangle& tri = scene.triangles[prim.index()];
            if (!scene.meshes[tri.mesh].has_uvs) return {u, v};
            const Vec2 t0 = scene.uvs[tri.v[0]], t1 = scene.uvs[tri.v[1]], t2 = scene.uvs[tri.v[2]];
            const float w = 1.0f - u - v;
            return {w * t0.x + u * t1.x + v * t2.x, w * t0.y + u * t1.y + v * t2.y};
        }
        case PrimKind::Quad:
            return {u, v};
        case PrimKind::Sphere: {
            const Sphere& s = scene.spheres[prim.index()];
            return sphere_uv((p - s.center) / s.radius);
        }
    }
    return {};
}

bool cut_away(const Scene& scene, PrimRef prim, float t, float u, float v, const Ray& ray) {
    const MaterialId m = scene.prim_material(prim);
    if (m == kNone || scene.materials[m].opacity == kNone) return false;
    const Point3 p = ray.at(t);
    const Color c =
        eval_texture(scene, scene.materials[m].opacity, hit_uv(scene, prim, u, v, p), p);
    const float a = std::clamp(0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z, 0.0f, 1.0f);
    if (a >= 1.0f) return false;
    if (a <= 0.0f) return true;
    return hash_float(ray, prim) >= a;
}

}  // namespace wavetrace
