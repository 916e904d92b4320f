#include "scene/material_lookup.h"

#include <algorithm>

#include "bsdfs/metallic_roughness.h"
#include "bsdfs/principled.h"
#include "scene/normal_maps.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

bool material_reads_uv(const Scene& scene, const Material& m) {
    bool reads = m.has_normal_maps();
    for (const TextureId t :
         {m.albedo, m.emission, m.metallic_roughness, m.clearcoat_map, m.clearcoat_roughness_map,
          m.alpha_u_texture, m.alpha_v_texture, m.transmission_map})
        reads = reads || texture_reads_uv(scene, t);
    if (m.kind == MaterialKind::Principled)
        m.principled.for_each([&](const char*, const TexturedNumber& w) {
            reads = reads || texture_reads_uv(scene, w.texture);
        });
    if (m.kind == MaterialKind::Blend) {
        reads = reads || texture_reads_uv(scene, m.blend_weight.texture);
        for (const MaterialId b : m.blend)
            reads = reads || material_reads_uv(scene, scene.materials[b]);
    }
    return reads;
}

std::vector<std::string> material_attributes(const Scene& scene, MaterialId id) {
    std::vector<std::string> names;
    if (id == kNone || id >= scene.materials.size()) return names;
    const Material& m = scene.materials[id];
    for (const TextureId t :
         {m.albedo, m.metallic_roughness, m.alpha_u_texture, m.alpha_v_texture, m.opacity})
        texture_attributes(scene, t, &names);
    if (m.kind == MaterialKind::Blend) {
        texture_attributes(scene, m.blend_weight.texture, &names);
        for (const MaterialId b : m.blend)  // materials before it (check_scene): this ends
            if (b < id)
                for (std::string& n : material_attributes(scene, b)) names.push_back(std::move(n));
    }
    return names;
}

const char* attribute_misuse(const Scene& scene, const Material& m) {
    auto reads = [&](TextureId id) { return texture_reads_attributes(scene, id); };
    if (reads(m.emission)) return "emission";
    if (reads(m.normal_map)) return "normal_map";
    if (reads(m.bump_map)) return "bump_map";
    if (reads(m.clearcoat_normal_map)) return "clearcoat_normal_map";
    if (reads(m.transmission_map)) return "transmission_texture";
    if (reads(m.clearcoat_map)) return "clearcoat_texture";
    if (reads(m.clearcoat_roughness_map)) return "clearcoat_roughness_texture";
    const char* weight = nullptr;
    m.principled.for_each([&](const char* name, const TexturedNumber& w) {
        if (!weight && reads(w.texture)) weight = name;
    });
    return weight;
}

namespace {

// Texture t at `at`, each channel clamped to [0, 1].
Color unit_texture_at(const Scene& scene, TextureId t, const TexturePoint& at) {
    const Color c = eval_texture(scene, t, at);
    return {std::clamp(c.x, 0.0f, 1.0f), std::clamp(c.y, 0.0f, 1.0f), std::clamp(c.z, 0.0f, 1.0f)};
}

}  // namespace

void metallic_roughness_at(const Scene& scene,
                           const Material& m,
                           const TexturePoint& at,
                           BsdfParams* b) {
    if (m.metallic_roughness != kNone) {
        const Color t = unit_texture_at(scene, m.metallic_roughness, at);
        const float roughness = m.roughness * t.y;
        b->alpha = b->alpha_v = roughness * roughness;
        b->metallic = m.metallic * t.z;
    }
    transmission_and_coat_at(scene, m, at, b);
}

void transmission_and_coat_at(const Scene& scene,
                              const Material& m,
                              const TexturePoint& at,
                              BsdfParams* b) {
    if (m.transmission_map != kNone)
        b->transmission = m.transmission * unit_texture_at(scene, m.transmission_map, at).x;
    if (m.clearcoat_map != kNone)
        b->clearcoat = m.clearcoat * unit_texture_at(scene, m.clearcoat_map, at).x;
    if (m.clearcoat_roughness_map != kNone) {
        const float roughness =
            m.clearcoat_roughness * unit_texture_at(scene, m.clearcoat_roughness_map, at).y;
        b->clearcoat_alpha = roughness * roughness;
    }
}

float emission_through_coat(const Scene& scene, const Material& m, const MappedPoint& at, Vec3 wo) {
    BsdfParams coat;
    coat.clearcoat = m.clearcoat;
    transmission_and_coat_at(scene, m, {at.uv, at.p}, &coat);
    const float oc = dot(coat_normal(scene, m, at), wo) * (dot(at.ng, wo) < 0.0f ? -1.0f : 1.0f);
    return coat_emission_weight(coat.clearcoat, oc);
}

MaterialId blend_choice(const Scene& scene, MaterialId m, const TexturePoint& at, float u) {
    while (m != kNone && scene.materials[m].kind == MaterialKind::Blend) {
        const Material& b = scene.materials[m];
        const TexturedNumber& x = b.blend_weight;
        const float w =
            std::clamp(x.texture == kNone ? x.value : luminance(eval_texture(scene, x.texture, at)),
                       0.0f, 1.0f);
        if (u < w) {
            m = b.blend[1];
            u = u / w;
        } else {
            m = b.blend[0];
            u = w < 1.0f ? (u - w) / (1.0f - w) : 0.0f;
        }
        u = std::min(u, 0x1.fffffep-1f);
    }
    return m;
}

void principled_at(const Scene& scene, const Material& m, Vec2 uv, Point3 p, BsdfParams* b) {
    const PrincipledWeights& w = m.principled;
    auto at = [&](const TexturedNumber& x) {
        return x.texture == kNone ? x.value : luminance(eval_texture(scene, x.texture, uv, p));
    };
    auto unit = [&](const TexturedNumber& x) { return std::clamp(at(x), 0.0f, 1.0f); };
    PrincipledLobes& l = b->principled;
    l.thin = w.thin;
    l.roughness = unit(w.roughness);
    l.anisotropic = unit(w.anisotropic);
    l.spec_tint = unit(w.spec_tint);
    l.sheen = unit(w.sheen);
    l.sheen_tint = unit(w.sheen_tint);
    l.flatness = unit(w.flatness);
    l.diff_trans = w.thin ? 0.5f * std::clamp(at(w.diff_trans), 0.0f, 2.0f) : 0.0f;
    b->metallic = w.thin ? 0.0f : unit(w.metallic);
    b->transmission = unit(w.spec_trans);
    b->clearcoat = w.thin ? 0.0f : unit(w.clearcoat);
    // GTR1's alpha from the gloss, 0.1 (0) to 0.001 (1) (Burley 2012, B.2).
    b->clearcoat_alpha = 0.1f + (0.001f - 0.1f) * unit(w.clearcoat_gloss);
    principled_alphas(l.roughness, l.anisotropic, &b->alpha, &b->alpha_v);
}

}  // namespace wavetrace
