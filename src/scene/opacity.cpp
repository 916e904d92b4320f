#include "scene/opacity.h"

#include <algorithm>
#include <bit>
#include <cstdint>

#include "sampling/sampler-inl.h"
#include "scene/hit_geometry.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
namespace {

// A uniform number in [0, 1) from the ray and the primitive.
float hash_float(const Ray& ray, PrimRef prim) {
    using lanes::Mix64, lanes::OneLane;
    uint64_t h = Mix64<OneLane>(0x9e3779b97f4a7c15ull ^ prim.bits);
    for (float f : {ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z})
        h = Mix64<OneLane>(h ^ std::bit_cast<uint32_t>(f));
    return float(h >> 40) * 0x1p-24f;
}

}  // namespace

bool has_alpha_masks(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.opacity != kNone; });
}

bool cut_away(const Scene& scene, PrimRef prim, float t, float u, float v, const Ray& ray) {
    const MaterialId m = scene.prim_material(prim);
    if (m == kNone || scene.materials[m].opacity == kNone) return false;
    const Point3 p = ray.at(t);
    const Color c =
        eval_texture(scene, scene.materials[m].opacity, hit_uv(scene, prim, u, v, p), p);
    const float a = std::clamp(luminance(c), 0.0f, 1.0f);
    if (a >= 1.0f) return false;
    if (a <= 0.0f) return true;
    return hash_float(ray, prim) >= a;
}

}  // namespace wavetrace
