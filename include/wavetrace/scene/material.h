#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "wavetrace/bsdfs/coating.h"
#include "wavetrace/bsdfs/material_kind.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

const char* to_string(MaterialKind kind);

// A number, or a texture in its place: the luminance of the texture at the point (kNone: the
// number).
struct TexturedNumber {
    float value = 0.0f;
    TextureId texture = kNone;
};

// The weights of a principled material (Mitsuba 3's principled and principledthin,
// bsdfs/principled.h), each in [0, 1] but diff_trans, in [0, 2] as Mitsuba has it.
struct PrincipledWeights {
    TexturedNumber metallic, roughness{0.5f}, anisotropic, spec_trans, spec_tint, sheen, sheen_tint,
        flatness, clearcoat, clearcoat_gloss, diff_trans;
    bool thin = false;  // principledthin: a sheet with diffuse transmission, no clearcoat
    // Whether the full (thin false) or the thin material has the weight `name`: diff_trans only
    // the sheet; metallic, clearcoat and clearcoat_gloss only the full one.
    static bool has(std::string_view name, bool thin) {
        if (name == "diff_trans") return thin;
        return !thin || (name != "metallic" && name != "clearcoat" && name != "clearcoat_gloss");
    }
    // The largest value of the weight `name`: 2 for diff_trans (Mitsuba's range), else 1.
    static float max_of(std::string_view name) { return name == "diff_trans" ? 2.0f : 1.0f; }
    // Each weight with its name in scene files, in this order.
    template <typename F>
    void for_each(F&& f) {
        each(*this, f);
    }
    template <typename F>
    void for_each(F&& f) const {
        each(*this, f);
    }

  private:
    template <typename Self, typename F>
    static void each(Self& w, F& f) {
        f("metallic", w.metallic);
        f("roughness", w.roughness);
        f("anisotropic", w.anisotropic);
        f("spec_trans", w.spec_trans);
        f("spec_tint", w.spec_tint);
        f("sheen", w.sheen);
        f("sheen_tint", w.sheen_tint);
        f("flatness", w.flatness);
        f("clearcoat", w.clearcoat);
        f("clearcoat_gloss", w.clearcoat_gloss);
        f("diff_trans", w.diff_trans);
    }
};

struct Material {
    std::string name;
    MaterialKind kind = MaterialKind::Lambertian;
    TextureId albedo = kNone;    // Lambertian, Metal, Mirror, Isotropic; Conductor: a factor on
                                 // the Fresnel reflectance (Mitsuba's specular_reflectance);
                                 // Plastic: the diffuse base's reflectance; MetallicRoughness:
                                 // the base colour
    float roughness = 0.0f;      // Metal, MetallicRoughness
    float ior = 1.5f;            // Dielectric; Plastic: the coating's
    // DiffuseLight, MetallicRoughness: emitted radiance (W sr^-1 m^-2 per channel; kNone: none)
    TextureId emission = kNone;
    bool two_sided = false;  // emits from both sides
    // Lambertian, Metal, Mirror, Conductor, Plastic: reflects nothing from behind (Mitsuba's
    // diffuse, conductor, ...; its `twosided` wrapper is the default here).
    bool one_sided = false;
    // Conductor: the index of refraction eta + i k per channel, relative to the outside.
    // Conductor, Dielectric and Plastic: the microfacet roughness along the shading frame's two
    // tangents (0, 0: smooth; Plastic: isotropic, alpha_u) and its distribution.
    Color eta{0.0f}, k{0.0f};
    Microfacet distribution = Microfacet::Ggx;
    float alpha_u = 0.0f, alpha_v = 0.0f;
    // Conductor: alpha_u and alpha_v from textures instead (kNone: the numbers above), the first
    // channel at the hit clamped to [1e-4, 1] (Mitsuba's roughconductor alpha textures). Where
    // one is set its number above only says "rough" (> 0).
    TextureId alpha_u_texture = kNone, alpha_v_texture = kNone;
    // Plastic (Mitsuba 3's plastic and roughplastic): the coating's specular reflectance, and
    // whether the base's inner bounces are nonlinear in its reflectance.
    Color specular{1.0f};
    bool nonlinear = false;
    // Plastic, derived by Scene::add_material: the probability weight of the specular lobe,
    // mean(specular) / (mean(specular) + mean(albedo)) over the albedo texture, and the rough
    // coating's table.
    float specular_weight = 0.5f;
    CoatingTable coating;

    // MetallicRoughness (glTF 2.0's pbrMetallicRoughness, KHR_materials_transmission and
    // _clearcoat): metallic, transmission and clearcoat factors, the clearcoat's roughness, and
    // glTF's metallicRoughnessTexture (kNone: none), whose green channel multiplies `roughness`
    // and blue channel `metallic`, its transmissionTexture, whose red channel multiplies
    // `transmission`, its clearcoatTexture, whose red channel multiplies `clearcoat`, and its
    // clearcoatRoughnessTexture, whose green channel multiplies `clearcoat_roughness`.
    float metallic = 1.0f, transmission = 0.0f, clearcoat = 0.0f, clearcoat_roughness = 0.0f;
    TextureId metallic_roughness = kNone, transmission_map = kNone, clearcoat_map = kNone,
              clearcoat_roughness_map = kNone;

    // Principled: albedo is the base colour, ior the index of refraction; the lobes' weights.
    PrincipledWeights principled;

    // Blend (Mitsuba 3's blendbsdf, pbrt-v4's mix): the materials blend[0] and blend[1], added
    // before it, mixed as (1 - w) f0 + w f1 with w = blend_weight at the hit, clamped to [0, 1].
    // Each hit takes blend[1] with probability w and blend[0] otherwise (pbrt-v4's
    // MixMaterial), which has that mixture as its expected value; shading/surface.h.
    TexturedNumber blend_weight{0.5f};
    MaterialId blend[2] = {kNone, kNone};

    // Any surface material: an alpha mask, the surface cut away where the texture's luminance
    // is below 1 (kNone: opaque; src/scene/opacity.h).
    TextureId opacity = kNone;
    // Any surface material: a normal map (a raw image: tangent-space normals as 2 rgb - 1) or a
    // bump map (heights, scaled by bump_scale) perturbing the shading normal
    // (src/scene/normal_maps.h); kNone: none. MetallicRoughness: glTF's clearcoatNormalTexture,
    // the coat's own normal map over the unperturbed shading normal (without one the coat keeps
    // that normal, not normal_map's).
    TextureId normal_map = kNone;
    TextureId bump_map = kNone;
    TextureId clearcoat_normal_map = kNone;
    float bump_scale = 1.0f;
    // Mitsuba 3's two corrections of a mapped normal (both off by default here, on in its
    // `normalmap` and `bumpmap`): a mapped normal facing away from the viewer is mirrored about
    // the shading normal (flip_invalid_normals), and light is shadowed near the terminator as
    // Estevez et al. 2019 derive (bump_shadowing; src/bsdfs/bump_terminator.h).
    bool flip_invalid_normals = false;
    bool bump_shadowing = false;
    bool has_normal_maps() const {
        return normal_map != kNone || bump_map != kNone || clearcoat_normal_map != kNone;
    }
    // Whether its roughness may differ along dp/du (alpha_u) and across it (alpha_v).
    bool anisotropic() const {
        if (kind == MaterialKind::Principled)
            return principled.anisotropic.value != 0.0f || principled.anisotropic.texture != kNone;
        return alpha_u != alpha_v || alpha_u_texture != alpha_v_texture;
    }
    // Whether its shading frame must follow the surface's dp/du: normal and bump maps, and an
    // anisotropic roughness.
    bool needs_tangents() const { return has_normal_maps() || anisotropic(); }

    bool is_emissive() const { return emission != kNone; }
    // Whether a clearcoat lies over its emission, which then depends on the direction it leaves
    // in (KHR_materials_clearcoat; shading's emitted_radiance).
    bool coats_emission() const {
        return is_emissive() && kind == MaterialKind::MetallicRoughness && clearcoat > 0.0f;
    }
    // Whether it may be one of a blend's materials: a hit chooses among those once its surface
    // is shaded, so what is decided before (what emits, is cut away, passes shadow rays, bounds
    // a medium or scatters in one) must be the blend's own.
    bool can_be_blended() const {
        return !is_emissive() && opacity == kNone && kind != MaterialKind::DiffuseLight &&
               kind != MaterialKind::ThinDielectric && kind != MaterialKind::Interface &&
               kind != MaterialKind::Isotropic;
    }
};

}  // namespace wavetrace
