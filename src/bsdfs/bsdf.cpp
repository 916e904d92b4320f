#include "bsdfs/bsdf.h"

#include "bsdfs/conductor.h"
#include "bsdfs/diffuse-inl.h"
#include "bsdfs/metal-inl.h"
#include "bsdfs/metallic_roughness.h"
#include "bsdfs/plastic.h"
#include "bsdfs/principled.h"
#include "bsdfs/rough_dielectric.h"
#include "bsdfs/specular-inl.h"
#include "bsdfs/thin_dielectric.h"
#include "sampling/warp.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane, lanes::to_lanes, lanes::to_vec3;
namespace {

// w mirrored into the upper hemisphere when `side` is below it (and back): the front-side lobes
// of two-sided shading.
Vec3 upper(Vec3 w, Vec3 side) {
    return side.z < 0.0f ? Vec3{w.x, w.y, -w.z} : w;
}

// A Dirac-delta lobe of b (mirror, smooth metal, conductor or dielectric): specular-inl.h's
// one-lane instance.
BsdfSample specular_sample(const BsdfParams& b, Vec3 wo, float u_lobe) {
    const lanes::GlossyLobeSample<OneLane> l =
        lanes::SpecularLocal<OneLane>(to_lanes(b), to_lanes(wo), u_lobe);
    BsdfSample s;
    s.wi = to_vec3(l.wi);
    s.weight = to_vec3(l.weight);
    s.transmitted = l.transmitted;
    s.delta = s.valid = l.valid;
    return s;
}

}  // namespace

float ggx_d(Vec3 h, float alpha) {
    return lanes::GgxD<OneLane>(h.z, alpha);
}

float ggx_g1(Vec3 w, float alpha) {
    return lanes::GgxG1<OneLane>(w.z, alpha);
}

Vec3 ggx_sample_visible_normal(Vec3 wo, float alpha, float u1, float u2) {
    return to_vec3(lanes::GgxVisibleNormal<OneLane>(to_lanes(wo), alpha, alpha, u1, u2));
}

Color bsdf_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    *pdf = 0.0f;
    switch (b.kind) {
        case MaterialKind::Lambertian:
            return to_vec3(lanes::LambertianEval<OneLane>(to_lanes(b.albedo), wo.z, wi.z, pdf));
        case MaterialKind::Metal:
            if (b.alpha == 0.0f) return {};
            return to_vec3(lanes::MetalEval<OneLane>(to_lanes(b.albedo), b.alpha, to_lanes(wo),
                                                     to_lanes(wi), pdf));
        case MaterialKind::Isotropic:
            return to_vec3(lanes::PhaseEval<OneLane>(to_lanes(b.albedo), pdf));
        case MaterialKind::Conductor:
            return conductor_eval(b, wo, wi, pdf);
        case MaterialKind::Dielectric:
            if (b.alpha == 0.0f) return {};
            return rough_dielectric_eval(b, wo, wi, pdf);
        case MaterialKind::Plastic:
            if (b.one_sided && wo.z < 0.0f) return {};
            return plastic_eval(b, upper(wo, wo), upper(wi, wo), pdf);
        case MaterialKind::MetallicRoughness:
            return metallic_roughness_eval(b, wo, wi, pdf);
        case MaterialKind::Principled:
            return principled_eval(b, wo, wi, pdf);
        default:
            return {};  // delta lobes, emitters and interfaces do not scatter smoothly
    }
}

Color bsdf_eval(const BsdfParams& b, Vec3 wo, Vec3 wi) {
    float pdf;
    return bsdf_eval(b, wo, wi, &pdf);
}

float bsdf_pdf(const BsdfParams& b, Vec3 wo, Vec3 wi) {
    float pdf;
    bsdf_eval(b, wo, wi, &pdf);
    return pdf;
}

BsdfSample bsdf_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2) {
    BsdfSample s;
    if (wo.z == 0.0f && b.kind != MaterialKind::Isotropic) return s;
    // Reflective lobes work on wo's side of the surface: both directions mirrored into the
    // upper hemisphere when wo is below (two-sided shading, as Ray Tracing in One Weekend's
    // front_face flip).
    const float side = lanes::SideOf<OneLane>(to_lanes(wo));
    switch (b.kind) {
        case MaterialKind::Lambertian: {
            s.wi = to_vec3(lanes::Upper<OneLane>(to_lanes(sample_cosine_hemisphere(u1, u2)), side));
            s.pdf = lanes::LambertianPdf<OneLane>(s.wi.z);
            s.weight = b.albedo;
            s.valid = s.pdf > 0.0f;
            return s;
        }
        case MaterialKind::Metal: {
            if (b.alpha == 0.0f) return specular_sample(b, wo, u_lobe);
            // A sample reflected below the surface is lost (valid = false).
            const lanes::ReflectionSample<OneLane> m =
                lanes::MetalSample<OneLane>(to_lanes(b.albedo), b.alpha, to_lanes(wo), u1, u2);
            if (!m.valid) return s;
            s.wi = to_vec3(m.wi);
            s.pdf = m.pdf;
            s.weight = to_vec3(m.weight);
            s.valid = true;
            return s;
        }
        case MaterialKind::Mirror:
            return specular_sample(b, wo, u_lobe);
        case MaterialKind::Dielectric:
            if (b.alpha > 0.0f) return rough_dielectric_sample(b, wo, u_lobe, u1, u2);
            return specular_sample(b, wo, u_lobe);
        case MaterialKind::Conductor:
            if (b.is_delta()) return specular_sample(b, wo, u_lobe);
            return conductor_sample(b, wo, u1, u2);
        case MaterialKind::ThinDielectric:
            return thin_dielectric_sample(b, wo, u_lobe);
        case MaterialKind::Plastic: {
            if (b.one_sided && wo.z < 0.0f) return s;
            s = plastic_sample(b, upper(wo, wo), u_lobe, u1, u2);
            s.wi = upper(s.wi, wo);
            return s;
        }
        case MaterialKind::MetallicRoughness:
            return metallic_roughness_sample(b, wo, u_lobe, u1, u2);
        case MaterialKind::Principled:
            return principled_sample(b, wo, u_lobe, u1, u2);
        case MaterialKind::Isotropic:
            s.wi = sample_uniform_sphere(u1, u2);
            s.pdf = lanes::PhasePdf<OneLane>();
            s.weight = b.albedo;
            s.valid = true;
            return s;
        default:
            return s;
    }
}

}  // namespace wavetrace
