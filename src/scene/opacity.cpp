#include "scene/opacity.h"

#include <algorithm>

#include "scene/hit_geometry.h"
#include "scene/hit_hash.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {
bool has_alpha_masks(const Scene& scene) {
    return std::any_of(scene.materials.begin(), scene.materials.end(),
                       [](const Material& m) { return m.opacity != kNone; });
}

bool cut_away(const Scene& scene, PrimRef prim, float t, float u, float v, const Ray& ray) {
    const MaterialId m = scene.prim_material(prim);
    if (m == kNone || scene.materials[m].opacity == kNone) return false;
    const Point3 p = ray.at(t);
    const bool triangle = prim.kind() == PrimKind::Triangle;
    const Color c =
        eval_texture(scene, scene.materials[m].opacity,
                     {hit_uv(scene, prim, u, v, p), p, triangle ? prim.index() : kNone, u, v});
    const float a = std::clamp(luminance(c), 0.0f, 1.0f);
    if (a >= 1.0f) return false;
    if (a <= 0.0f) return true;
    return hit_hash(ray, prim, HitDecision::Opacity) >= a;
}

}  // namespace wavetrace
