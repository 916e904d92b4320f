// Scattering at a surface or medium vertex, for every material kind: evaluate, sample, pdf.
// Shared by both engines. All directions are unit vectors in the shading frame's local
// coordinates (z along the shading normal on the side the light arrives from is NOT assumed:
// wo may be on either side), pointing away from the vertex.
//
// Contract (as Mitsuba's BSDF::eval/sample): eval() returns f(wo, wi) |cos theta_i| — the
// cosine is included — and 0 for delta lobes; pdf() is the solid-angle density with which
// sample() picks wi (0 for delta lobes); sample() returns wi and weight = f |cos| / pdf (for
// delta lobes the lobe's throughput). For the isotropic phase function "cos" is 1.
#pragma once

#include "microfacets/microfacet.h"
#include "wavetrace/bsdfs/coating.h"
#include "wavetrace/bsdfs/material_kind.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// The lobe weights of a principled BSDF (bsdfs/principled.h) at one point, each in [0, 1].
struct PrincipledLobes {
    float roughness = 0.5f, anisotropic = 0.0f, spec_tint = 0.0f, sheen = 0.0f, sheen_tint = 0.0f,
          flatness = 0.0f;
    float diff_trans = 0.0f;  // thin: the diffuse transmission, Mitsuba's diff_trans / 2
    bool thin = false;        // principledthin
};

// A material resolved at one point: the kind and its parameters with textures evaluated.
struct BsdfParams {
    MaterialKind kind = MaterialKind::Lambertian;
    Color albedo{0.0f};
    float alpha = 0.0f;  // Metal: GGX roughness alpha = roughness^2 (0: a perfect mirror);
                         // Conductor, Dielectric: the microfacet roughness alpha_u (0: smooth)
    float eta = 1.0f;    // Dielectric: IOR inside / IOR outside as seen by the ray (front: ior)
    // Conductor (bsdfs/conductor.h): the complex index of refraction; Conductor and rough
    // Dielectric (bsdfs/rough_dielectric.h): the roughness along the frame's y axis and the
    // distribution.
    Color conductor_eta{1.0f}, conductor_k{0.0f};
    float alpha_v = 0.0f;
    Microfacet distribution = Microfacet::Ggx;
    // Plastic (bsdfs/plastic.h): albedo is the base's reflectance, eta the coating's, alpha its
    // roughness (isotropic; 0: smooth); the specular reflectance, the probability weight of the
    // specular lobe, the nonlinear rule, and the rough coating's table; one_sided: black from
    // behind (wo.z < 0) rather than mirrored to the front.
    Color specular{1.0f};
    float specular_weight = 0.5f;
    bool nonlinear = false;
    bool one_sided = false;
    const CoatingTable* coating = nullptr;
    // MetallicRoughness (bsdfs/metallic_roughness.h): albedo is the base colour, alpha the GGX
    // roughness^2, eta the index of refraction giving F0; metallic, transmission and clearcoat
    // in [0, 1], the clearcoat's GGX alpha and its normal (unit, in the shading frame, on the
    // side of its z; zero: the shading normal, so that a vertex's zeroed state says it);
    // one_sided as for Plastic.
    float metallic = 0.0f, transmission = 0.0f, clearcoat = 0.0f, clearcoat_alpha = 0.0f;
    Vec3 coat_normal{0.0f};
    // Principled (bsdfs/principled.h): albedo is the base colour, eta the index of refraction of
    // the surface's inside over its front's, metallic, transmission (spec_trans) and clearcoat
    // as for MetallicRoughness, clearcoat_alpha the GTR1 alpha; the other lobes here.
    PrincipledLobes principled;

    // Every lobe is a Dirac delta: never light-sampled. Inline: both engines ask it at every
    // vertex.
    bool is_delta() const {
        return kind == MaterialKind::Mirror || kind == MaterialKind::ThinDielectric ||
               (kind == MaterialKind::Dielectric && alpha == 0.0f) ||
               (kind == MaterialKind::Metal && alpha == 0.0f) ||
               (kind == MaterialKind::Conductor && alpha == 0.0f && alpha_v == 0.0f) ||
               (kind == MaterialKind::MetallicRoughness && metallic == 1.0f && alpha == 0.0f &&
                (clearcoat == 0.0f || clearcoat_alpha == 0.0f));
    }
    // Whether a metallic-roughness coat lies along the shading normal, and its normal.
    bool coat_along_normal() const { return coat_normal.x == 0.0f && coat_normal.y == 0.0f; }
    Vec3 coat_normal_or_z() const {
        return coat_along_normal() ? Vec3{0.0f, 0.0f, 1.0f} : coat_normal;
    }
};

// The distribution of a rough conductor or dielectric.
inline MicrofacetDistribution microfacet_of(const BsdfParams& b) {
    return {b.distribution, b.alpha, b.alpha_v};
}

struct BsdfSample {
    Vec3 wi;
    Color weight{0.0f};  // f |cos| / pdf, or the delta lobe's throughput
    float pdf = 0.0f;    // solid angle; 0 for delta lobes
    bool delta = false;
    bool transmitted = false;  // wi crossed the surface
    bool valid = false;
};

// f |cos theta_i| of wo, wi in the shading frame, and the density of sampling wi in *pdf.
Color bsdf_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf);
Color bsdf_eval(const BsdfParams& b, Vec3 wo, Vec3 wi);
float bsdf_pdf(const BsdfParams& b, Vec3 wo, Vec3 wi);
// u_lobe picks between lobes (dielectric reflection/refraction); (u1, u2) the direction.
BsdfSample bsdf_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2);

// GGX (Trowbridge-Reitz) pieces, exposed for tests.
float ggx_d(Vec3 h, float alpha);
float ggx_g1(Vec3 w, float alpha);
// A visible normal for wo (wo.z > 0): Heitz, "Sampling the GGX Distribution of Visible
// Normals", JCGT 7(4), 2018.
Vec3 ggx_sample_visible_normal(Vec3 wo, float alpha, float u1, float u2);

}  // namespace wavetrace
