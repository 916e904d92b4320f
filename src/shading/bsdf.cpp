#include "wavetrace/shading/bsdf.h"

#include <algorithm>
#include <cmath>

#include "shading/warp.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace {

// Reflective lobes work on wo's side of the surface: mirror both directions into the upper
// hemisphere when wo is below (two-sided shading, as the seed's front_face flip).
inline Vec3 upper(Vec3 w, float side) {
    return {w.x, w.y, w.z * side};
}
inline float side_of(Vec3 wo) {
    return wo.z < 0.0f ? -1.0f : 1.0f;
}

// Schlick's approximation with the albedo as the reflectance at normal incidence: the
// seed's metal tint, made angle-dependent (Schlick 1994).
inline Color schlick(Color f0, float cos_theta) {
    float m = std::clamp(1.0f - cos_theta, 0.0f, 1.0f);
    float m5 = (m * m) * (m * m) * m;
    return f0 + (Color(1.0f) - f0) * m5;
}

// Smith's Lambda for GGX: (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2 (Heitz 2014, eq. 72).
inline float ggx_lambda(Vec3 w, float alpha) {
    float cos2 = w.z * w.z;
    if (cos2 <= 0.0f) return kInfinity;
    float tan2 = std::max(0.0f, 1.0f - cos2) / cos2;
    return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}

}  // namespace

bool BsdfParams::is_delta() const {
    return kind == MaterialKind::Mirror || kind == MaterialKind::Dielectric ||
           (kind == MaterialKind::Metal && alpha == 0.0f);
}

float ggx_d(Vec3 h, float alpha) {
    if (h.z <= 0.0f) return 0.0f;
    float a2 = alpha * alpha;
    float t = h.z * h.z * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * t * t);
}

float ggx_g1(Vec3 w, float alpha) {
    return 1.0f / (1.0f + ggx_lambda(w, alpha));
}

Vec3 ggx_sample_visible_normal(Vec3 wo, float alpha, float u1, float u2) {
    // Stretch to the hemisphere configuration, sample the projected half-disk, unstretch.
    Vec3 vh = normalize(Vec3{alpha * wo.x, alpha * wo.y, wo.z});
    float lensq = vh.x * vh.x + vh.y * vh.y;
    Vec3 t1 = lensq > 0.0f ? Vec3{-vh.y, vh.x, 0.0f} / std::sqrt(lensq) : Vec3{1.0f, 0.0f, 0.0f};
    Vec3 t2 = cross(vh, t1);
    float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    float p1 = r * std::cos(phi), p2 = r * std::sin(phi);
    float s = 0.5f * (1.0f + vh.z);
    p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * p2;
    Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return normalize(Vec3{alpha * nh.x, alpha * nh.y, std::max(1e-7f, nh.z)});
}

float fresnel_dielectric(float cos_i, float eta) {
    float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
    float cos_t = std::sqrt(1.0f - sin2_t);
    float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

Color bsdf_eval(const BsdfParams& b, Vec3 wo, Vec3 wi) {
    switch (b.kind) {
        case MaterialKind::Lambertian:
            if (wo.z * wi.z <= 0.0f) return {};
            return b.albedo * (kInvPi * std::fabs(wi.z));
        case MaterialKind::Metal: {
            if (b.alpha == 0.0f || wo.z * wi.z <= 0.0f) return {};
            float side = side_of(wo);
            Vec3 o = upper(wo, side), i = upper(wi, side);
            Vec3 h = normalize(o + i);
            // f cos_i = F D G2 / (4 cos_o), with the height-correlated Smith G2.
            float g2 = 1.0f / (1.0f + ggx_lambda(o, b.alpha) + ggx_lambda(i, b.alpha));
            return schlick(b.albedo, dot(i, h)) * (ggx_d(h, b.alpha) * g2 / (4.0f * o.z));
        }
        case MaterialKind::Isotropic:
            return b.albedo * (0.25f * kInvPi);
        default:
            return {};  // delta lobes, emitters and interfaces do not scatter smoothly
    }
}

float bsdf_pdf(const BsdfParams& b, Vec3 wo, Vec3 wi) {
    switch (b.kind) {
        case MaterialKind::Lambertian:
            return wo.z * wi.z <= 0.0f ? 0.0f : kInvPi * std::fabs(wi.z);
        case MaterialKind::Metal: {
            if (b.alpha == 0.0f || wo.z * wi.z <= 0.0f) return 0.0f;
            float side = side_of(wo);
            Vec3 o = upper(wo, side), i = upper(wi, side);
            Vec3 h = normalize(o + i);
            // Visible-normal density D_o(h) = G1(o) D(h) (o.h) / o.z, times the reflection
            // Jacobian 1 / (4 o.h).
            return ggx_g1(o, b.alpha) * ggx_d(h, b.alpha) / (4.0f * o.z);
        }
        case MaterialKind::Isotropic:
            return uniform_sphere_pdf();
        default:
            return 0.0f;
    }
}

BsdfSample bsdf_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2) {
    BsdfSample s;
    if (wo.z == 0.0f && b.kind != MaterialKind::Isotropic) return s;
    const float side = side_of(wo);
    switch (b.kind) {
        case MaterialKind::Lambertian: {
            s.wi = upper(sample_cosine_hemisphere(u1, u2), side);
            s.pdf = kInvPi * std::fabs(s.wi.z);
            s.weight = b.albedo;
            s.valid = s.pdf > 0.0f;
            return s;
        }
        case MaterialKind::Metal: {
            Vec3 o = upper(wo, side);
            if (b.alpha == 0.0f) {
                s.wi = {-wo.x, -wo.y, wo.z};
                s.weight = schlick(b.albedo, o.z);
                s.delta = s.valid = true;
                return s;
            }
            Vec3 h = ggx_sample_visible_normal(o, b.alpha, u1, u2);
            Vec3 i = 2.0f * dot(o, h) * h - o;
            if (i.z <= 0.0f) return s;  // reflected below the surface: the sample is lost
            // Recompute h from (o, i) exactly as bsdf_pdf/eval do, so that the returned pdf
            // and weight agree with them to the last bit (MIS relies on it).
            h = normalize(o + i);
            s.wi = upper(i, side);
            s.pdf = ggx_g1(o, b.alpha) * ggx_d(h, b.alpha) / (4.0f * o.z);
            // weight = F G2 / G1(o) for visible-normal sampling.
            float g2 = 1.0f / (1.0f + ggx_lambda(o, b.alpha) + ggx_lambda(i, b.alpha));
            s.weight = schlick(b.albedo, dot(i, h)) * (g2 / ggx_g1(o, b.alpha));
            s.valid = s.pdf > 0.0f;
            return s;
        }
        case MaterialKind::Mirror:
            s.wi = {-wo.x, -wo.y, wo.z};
            s.weight = b.albedo;
            s.delta = s.valid = true;
            return s;
        case MaterialKind::Dielectric: {
            // Relative IOR seen by the ray: entering from the front (wo.z > 0) goes into the
            // material; from the back it leaves it.
            float eta = wo.z > 0.0f ? b.eta : 1.0f / b.eta;
            float cos_i = std::fabs(wo.z);
            float f = fresnel_dielectric(cos_i, eta);
            s.delta = s.valid = true;
            if (u_lobe < f) {  // reflect with probability F: weight F / F = 1
                s.wi = {-wo.x, -wo.y, wo.z};
                s.weight = Color(1.0f);
                return s;
            }
            float cos_t = std::sqrt(std::max(0.0f, 1.0f - (1.0f - cos_i * cos_i) / (eta * eta)));
            // Snell: wt = -wo / eta + (cos_i / eta - cos_t) n, n on wo's side.
            s.wi = -wo / eta + Vec3{0.0f, 0.0f, side * (cos_i / eta - cos_t)};
            s.wi = normalize(s.wi);
            // Radiance is compressed by eta^2 entering a denser medium (Veach 1997, §5.2).
            s.weight = Color(1.0f / (eta * eta));
            s.transmitted = true;
            return s;
        }
        case MaterialKind::Isotropic:
            s.wi = sample_uniform_sphere(u1, u2);
            s.pdf = uniform_sphere_pdf();
            s.weight = b.albedo;
            s.valid = true;
            return s;
        default:
            return s;
    }
}

}  // namespace wavetrace
