#include "scene/normal_maps.h"

#include <cmath>

#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {
namespace {

constexpr float kBumpStep = 1.0f / 2048.0f;

// w without its component along unit n.
Vec3 in_plane(Vec3 w, Normal3 n) {
    return w - dot(n, w) * n;
}

bool usable(Vec3 v) {
    return length_squared(v) > 1e-24f && is_finite(v);
}

Normal3 bumped(const Scene& scene, const Material& m, const MappedPoint& hit, Normal3 n) {
    const Vec3 tu = in_plane(hit.dpdu, n), tv = in_plane(hit.dpdv, n);
    auto h = [&](float du, float dv) {
        return m.bump_scale *
               luminance(eval_texture(scene, m.bump_map, {hit.uv.x + du, hit.uv.y + dv}, hit.p));
    };
    Vec2 g;
    if (texture_luminance_gradient(scene, m.bump_map, hit.uv, &g)) {
        g = {m.bump_scale * g.x, m.bump_scale * g.y};
    } else {
        g = {(h(kBumpStep, 0) - h(-kBumpStep, 0)) / (2 * kBumpStep),
             (h(0, kBumpStep) - h(0, -kBumpStep)) / (2 * kBumpStep)};
    }
    const float dhdu = g.x, dhdv = g.y;
    Vec3 b = cross(tu + dhdu * n, tv + dhdv * n);
    if (!usable(b)) return n;
    b = normalize(b);
    return dot(b, n) < 0.0f ? -b : b;  // the side the unperturbed normal faces
}

// n tilted by the normal map `map`.
Normal3 normal_mapped(const Scene& scene, TextureId map, const MappedPoint& hit, Normal3 n) {
    Vec3 t = in_plane(hit.dpdu, n);
    if (!usable(t)) return n;
    t = normalize(t);
    Vec3 b = cross(n, t);
    if (dot(b, hit.dpdv) < 0.0f) b = -b;
    const Color c = eval_texture(scene, map, hit.uv, hit.p);
    const Vec3 local = 2.0f * c - Vec3(1.0f);
    const Vec3 w = local.x * t + local.y * b + local.z * n;
    return usable(w) ? normalize(w) : n;
}

}  // namespace

Normal3 mapped_normal(const Scene& scene, const Material& m, const MappedPoint& hit, Vec3 wo) {
    Normal3 n = hit.ns;
    if (m.bump_map != kNone) n = bumped(scene, m, hit, n);
    if (m.normal_map != kNone) n = normal_mapped(scene, m.normal_map, hit, n);
    if (dot(n, hit.ng) < 0.0f) n = -n;
    if (m.flip_invalid_normals && dot(wo, hit.ns) * dot(wo, n) <= 0.0f)
        n = 2.0f * dot(n, hit.ns) * hit.ns - n;
    return n;
}

Normal3 coat_normal(const Scene& scene, const Material& m, const MappedPoint& hit) {
    if (m.clearcoat_normal_map == kNone) return hit.ns;
    const Normal3 n = normal_mapped(scene, m.clearcoat_normal_map, hit, hit.ns);
    return dot(n, hit.ng) < 0.0f ? -n : n;
}

}  // namespace wavetrace
