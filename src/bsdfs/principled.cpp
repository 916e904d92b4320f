#include "bsdfs/principled.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/fresnel.h"
#include "microfacets/microfacet.h"
#include "sampling/warp.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace {

// Schlick's approximation with reflectance r0 at normal incidence, for light at cos_theta to a
// normal on the outside (cos_theta >= 0) of an interface of index eta or inside it; from the
// denser side the weight is taken at the refracted angle (1 under total internal reflection).
template <typename T>
T schlick(T r0, float cos_theta, float eta) {
    const float eta_it = cos_theta >= 0.0f ? eta : 1.0f / eta;
    float w;
    if (eta_it > 1.0f) {
        w = schlick_weight(std::fabs(cos_theta));
    } else {
        const float cos_t2 = 1.0f - (1.0f - cos_theta * cos_theta) * eta_it * eta_it;
        w = schlick_weight(std::sqrt(std::max(0.0f, cos_t2)));
    }
    return r0 * (1.0f - w) + T(w);
}

// Reflectance of a dielectric of index eta at normal incidence.
float r0_of(float eta) {
    const float r = (eta - 1.0f) / (eta + 1.0f);
    return r * r;
}

// The exact Fresnel reflectance for light at cos_theta to a normal, from either side.
float fresnel(float cos_theta, float eta) {
    return cos_theta >= 0.0f ? fresnel_dielectric(cos_theta, eta)
                             : fresnel_dielectric(-cos_theta, 1.0f / eta);
}

// c / lum(c): the base colour's hue at unit luminance (white where it is black).
Color tint_of(Color c) {
    const float lum = luminance(c);
    return lum > 0.0f ? c / lum : Color(1.0f);
}

// Smith's masking of direction v by microfacets of normal h: 0 where v sees h's back.
float masking(const MicrofacetDistribution& d, Vec3 v, Vec3 h) {
    return dot(v, h) * v.z > 0.0f ? d.g1(v) : 0.0f;
}
float masking2(const MicrofacetDistribution& d, Vec3 o, Vec3 i, Vec3 h) {
    return masking(d, o, h) * masking(d, i, h);
}

MicrofacetDistribution ggx_of(float roughness, float anisotropic) {
    MicrofacetDistribution d{Microfacet::Ggx, 0.0f, 0.0f};
    principled_alphas(roughness, anisotropic, &d.alpha_u, &d.alpha_v);
    return d;
}

// Burley's GTR1 ("generalized Trowbridge-Reitz", gamma 1) of the clearcoat, isotropic:
// D(m) = (a^2 - 1) / (pi ln(a^2) (1 + (a^2 - 1) cos^2)), sampled exactly (Burley 2012, B.2).
float gtr1_d(Vec3 m, float alpha) {
    if (m.z <= 0.0f) return 0.0f;
    const float a2 = alpha * alpha;
    return (a2 - 1.0f) / (kPi * std::log(a2) * (1.0f + (a2 - 1.0f) * m.z * m.z));
}
Vec3 gtr1_sample(float alpha, float u1, float u2) {
    const float a2 = alpha * alpha;
    const float cos2 = (1.0f - std::pow(a2, 1.0f - u2)) / (1.0f - a2);
    const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos2)),
                cos_t = std::sqrt(std::max(0.0f, cos2));
    const float phi = 2.0f * kPi * u1;
    return {std::cos(phi) * sin_t, std::sin(phi) * sin_t, cos_t};
}

Vec3 reflect(Vec3 o, Vec3 m) {
    return 2.0f * dot(o, m) * m - o;
}

// The diffuse reflection with Burley's retro-reflection, lerped towards the flatness lobe, and
// the sheen, without the weights they share: per unit of base colour and of sheen.
struct DiffuseSheen {
    float diffuse, sheen;
};
DiffuseSheen diffuse_sheen(const PrincipledLobes& l, float cos_o, float cos_i, float cos_d) {
    const float fo = schlick_weight(std::fabs(cos_o)), fi = schlick_weight(std::fabs(cos_i));
    const float lambert = (1.0f - 0.5f * fo) * (1.0f - 0.5f * fi);
    const float rr = 2.0f * l.roughness * cos_d * cos_d;
    const float retro = rr * (fo + fi + fo * fi * (rr - 1.0f));
    float diffuse = lambert + retro;
    if (l.flatness > 0.0f) {
        // Hanrahan-Krueger's single scattering in Burley's form (2012, B.1).
        const float fss90 = 0.5f * rr;
        const float fss = (1.0f + (fss90 - 1.0f) * fo) * (1.0f + (fss90 - 1.0f) * fi);
        const float ss =
            1.25f * (fss * (1.0f / (std::fabs(cos_o) + std::fabs(cos_i)) - 0.5f) + 0.5f);
        diffuse += l.flatness * (ss - diffuse);
    }
    return {diffuse * kInvPi, schlick_weight(std::fabs(cos_d))};
}

// The densities of a direction under each lobe's sampling, weighted by the lobe's probability;
// the BSDF's pdf is their sum. A sample whose direction has no density under the lobe that drew
// it (a reflection below the surface, a masked microfacet) is dropped, not weighted by the
// others' density: the samples kept are then distributed as pdf() says.
struct LobeDensities {
    float lobe[4] = {};
    float total() const { return lobe[0] + lobe[1] + lobe[2] + lobe[3]; }
};

// The sample of direction i that `lobe` drew, f |cos| and the densities there: dropped where
// that lobe has none.
BsdfSample kept_sample(Vec3 o, Vec3 i, int lobe, Color f, const LobeDensities& pdf) {
    BsdfSample s;
    if (!(pdf.lobe[lobe] > 0.0f)) return s;
    s.pdf = pdf.total();
    s.wi = i;
    s.weight = f / s.pdf;
    s.transmitted = o.z * i.z < 0.0f;
    s.valid = true;
    return s;
}

// --- principled ---------------------------------------------------------------------------

// Probabilities of the diffuse lobe, the clearcoat and the specular lobe for o (front: o.z > 0).
struct LobeChoice {
    float diffuse = 0.0f, coat = 0.0f, specular = 1.0f;
};
LobeChoice lobes_of(const BsdfParams& b, bool front) {
    if (!front) return {};
    const float brdf = (1.0f - b.metallic) * (1.0f - b.transmission);
    const float coat = b.clearcoat > 0.0f ? 0.25f * b.clearcoat : 0.0f;
    const float sum = 1.0f + coat + brdf;
    return {brdf / sum, coat / sum, 1.0f / sum};
}

// Within the specular lobe, the probability of transmission at a normal where the dielectric
// reflects F.
float transmission_share(const BsdfParams& b, bool front, float f) {
    const float bsdf = (1.0f - b.metallic) * b.transmission;
    if (front) return bsdf * (1.0f - f);
    if (!(bsdf > 0.0f)) return 0.0f;
    return 1.0f - f;  // from behind: reflection F, transmission 1 - F
}

// Lobes: 0 diffuse, 1 clearcoat, 2 specular reflection, 3 specular transmission.
Color principled_full_eval(const BsdfParams& b, Vec3 o, Vec3 i, LobeDensities* pdf) {
    const float co = o.z, ci = i.z;
    const bool reflect_ = co * ci > 0.0f, refract_ = co * ci < 0.0f;
    if (!reflect_ && !refract_) return {};
    const PrincipledLobes& l = b.principled;
    const bool front = co > 0.0f;
    const float m = b.metallic;
    const float brdf = (1.0f - m) * (1.0f - b.transmission), bsdf = (1.0f - m) * b.transmission;
    const float eta = b.eta, eta_path = front ? eta : 1.0f / eta;
    Vec3 h = normalize(o + i * (reflect_ ? 1.0f : eta_path));
    if (h.z < 0.0f) h = -h;
    const Vec3 hs = front ? h : -h;  // h on o's side
    const float oh = dot(o, h), ih = dot(i, h);
    const bool facets_reflect = dot(o, hs) > 0.0f && dot(i, hs) > 0.0f;
    const bool facets_refract = dot(o, hs) > 0.0f && dot(i, hs) < 0.0f;
    const float f = fresnel(oh, eta);
    const MicrofacetDistribution dist{Microfacet::Ggx, b.alpha, b.alpha_v};
    const float d = dist.d(h), g = masking2(dist, o, i, h);
    const LobeChoice p = lobes_of(b, front);
    const float share_t = transmission_share(b, front, f);
    const float share_r = front ? 1.0f - share_t : f;
    const float shares = share_r + share_t;
    const Vec3 o_up = front ? o : -o;

    Color value(0.0f);
    if (reflect_ && facets_reflect) {
        const float jacobian = 1.0f / (4.0f * std::fabs(ih));
        if (f > 0.0f) {
            Color fp(bsdf * f);
            if (front) {
                fp = Color((1.0f - m) * (1.0f - l.spec_tint) * f);
                if (m > 0.0f) fp += m * schlick(b.albedo, oh, eta);
                if (l.spec_tint > 0.0f) {
                    const float eta_it = oh >= 0.0f ? eta : 1.0f / eta;
                    fp += (1.0f - m) * l.spec_tint *
                          schlick(tint_of(b.albedo) * r0_of(eta_it), oh, eta);
                }
            }
            value += fp * (d * g / (4.0f * std::fabs(co)));
        }
        if (shares > 0.0f)
            pdf->lobe[2] = p.specular * (share_r / shares) * dist.visible_pdf(o_up, h) * jacobian;
        if (front && b.clearcoat > 0.0f) {
            const float alpha_c = b.clearcoat_alpha;
            const MicrofacetDistribution coat_masking{Microfacet::Ggx, 0.25f, 0.25f};
            const float fc = schlick(0.04f, oh, eta);
            value += Color(0.25f * b.clearcoat * fc * gtr1_d(h, alpha_c) *
                           masking2(coat_masking, o, i, h) * std::fabs(ci));
            pdf->lobe[1] = p.coat * gtr1_d(h, alpha_c) * h.z * jacobian;
        }
    }
    if (refract_ && facets_refract && bsdf > 0.0f) {
        const float denom = oh + eta_path * ih;
        if (f < 1.0f) {
            // Walter et al. 2007, eq. 21, for radiance (the eta^2 of importance cancelled).
            const float t = std::fabs((1.0f - f) * d * g * oh * ih / (co * denom * denom));
            value += Color(std::sqrt(b.albedo.x), std::sqrt(b.albedo.y), std::sqrt(b.albedo.z)) *
                     (bsdf * t);
        }
        if (shares > 0.0f) {
            const float jacobian = std::fabs(eta_path * eta_path * ih / (denom * denom));
            pdf->lobe[3] = p.specular * (share_t / shares) * dist.visible_pdf(o_up, h) * jacobian;
        }
    }
    if (reflect_ && front) {
        const DiffuseSheen ds = diffuse_sheen(l, co, ci, dot(h, i));
        if (brdf > 0.0f) {
            value += b.albedo * (brdf * ds.diffuse * std::fabs(ci));
            if (l.sheen > 0.0f && m < 1.0f) {
                const Color c_sheen =
                    Color(1.0f) + l.sheen_tint * (tint_of(b.albedo) - Color(1.0f));
                value += c_sheen * (l.sheen * (1.0f - m) * ds.sheen * std::fabs(ci));
            }
        }
        pdf->lobe[0] = p.diffuse * cosine_hemisphere_pdf(ci);
    }
    return value;
}

BsdfSample principled_full_sample(const BsdfParams& b, Vec3 o, float u_lobe, float u1, float u2) {
    if (o.z == 0.0f) return {};
    const bool front = o.z > 0.0f;
    const LobeChoice p = lobes_of(b, front);
    Vec3 i;
    int lobe;
    if (u_lobe < p.diffuse) {
        lobe = 0;
        i = sample_cosine_hemisphere(u1, u2);
    } else if (u_lobe < p.diffuse + p.coat) {
        lobe = 1;
        i = reflect(o, gtr1_sample(b.clearcoat_alpha, u1, u2));
    } else {
        const MicrofacetDistribution dist{Microfacet::Ggx, b.alpha, b.alpha_v};
        const Vec3 m = dist.sample_visible(front ? o : -o, u1, u2);
        const float om = dot(o, m), f = fresnel(om, b.eta);
        const float share_t = transmission_share(b, front, f);
        const float shares = (front ? 1.0f - share_t : f) + share_t;
        if (!(shares > 0.0f)) return {};
        // The lobe's part of u_lobe, rescaled to [0, 1), picks reflection or transmission.
        const float u = (u_lobe - p.diffuse - p.coat) / p.specular;
        if (u * shares < shares - share_t) {
            lobe = 2;
            i = reflect(o, m);
        } else {
            lobe = 3;
            // About the normal on o's side, into the material from its front.
            if (!refract(o, om >= 0.0f ? m : -m, om >= 0.0f ? b.eta : 1.0f / b.eta, &i))
                return {};  // total internal reflection
        }
    }
    LobeDensities pdf;
    const Color f = principled_full_eval(b, o, i, &pdf);
    return kept_sample(o, i, lobe, f, pdf);
}

// --- principledthin -----------------------------------------------------------------------

// The thin sheet's four lobes, whose probabilities sum to 1 whatever the weights.
struct ThinLobes {
    float spec_reflect, spec_transmit, diffuse_reflect, diffuse_transmit;
};
ThinLobes thin_lobes_of(const BsdfParams& b) {
    const float t = b.transmission, d = b.principled.diff_trans;
    return {0.5f * t, 0.5f * t, (1.0f - t) * (1.0f - d), (1.0f - t) * d};
}

// The transmission's distribution: the roughness scaled by 0.65 eta - 0.35 (Burley 2015).
MicrofacetDistribution thin_transmission_ggx(const BsdfParams& b) {
    return ggx_of((0.65f * b.eta - 0.35f) * b.principled.roughness, b.principled.anisotropic);
}

// Lobes: 0 specular reflection, 1 specular transmission, 2 diffuse reflection, 3 diffuse
// transmission.
Color principled_thin_eval(const BsdfParams& b, Vec3 o_in, Vec3 i_in, LobeDensities* pdf) {
    if (o_in.z == 0.0f) return {};
    // A sheet: seen from behind as from the front.
    const float side = o_in.z > 0.0f ? 1.0f : -1.0f;
    const Vec3 o = o_in * side, i = i_in * side;
    const bool reflect_ = i.z > 0.0f, refract_ = i.z < 0.0f;
    if (!reflect_ && !refract_) return {};
    const PrincipledLobes& l = b.principled;
    const float t = b.transmission, dt = l.diff_trans, co = o.z, ci = i.z;
    const Vec3 h = normalize(o + Vec3{i.x, i.y, std::fabs(i.z)});
    const float oh = dot(o, h);
    const ThinLobes p = thin_lobes_of(b);
    const float jacobian = 1.0f / (4.0f * std::fabs(dot(Vec3{i.x, i.y, std::fabs(i.z)}, h)));
    Color value(0.0f);
    if (reflect_) {
        if (oh > 0.0f && dot(i, h) > 0.0f) {
            const MicrofacetDistribution dist{Microfacet::Ggx, b.alpha, b.alpha_v};
            if (t > 0.0f) {
                const float f = fresnel(oh, b.eta);
                Color ft(f);
                if (l.spec_tint > 0.0f)
                    ft += l.spec_tint *
                          (schlick(tint_of(b.albedo) * r0_of(b.eta), oh, b.eta) - Color(f));
                value += ft * (t * dist.d(h) * masking2(dist, o, i, h) / (4.0f * co));
            }
            pdf->lobe[0] = p.spec_reflect * dist.visible_pdf(o, h) * jacobian;
        }
        const DiffuseSheen ds = diffuse_sheen(l, co, ci, dot(h, i));
        const float w = (1.0f - t) * (1.0f - dt) * ci;
        value += b.albedo * (w * ds.diffuse);
        if (l.sheen > 0.0f) {
            const Color c_sheen = Color(1.0f) + l.sheen_tint * (tint_of(b.albedo) - Color(1.0f));
            value += c_sheen * (l.sheen * ds.sheen * w);
        }
        pdf->lobe[2] = p.diffuse_reflect * cosine_hemisphere_pdf(ci);
    } else {
        if (oh > 0.0f && dot(i, h) < 0.0f) {
            const MicrofacetDistribution dist = thin_transmission_ggx(b);
            if (t > 0.0f) {
                const float f = fresnel(oh, b.eta);
                value +=
                    b.albedo * (t * (1.0f - f) * dist.d(h) * masking2(dist, o, i, h) / (4.0f * co));
            }
            pdf->lobe[1] = p.spec_transmit * dist.visible_pdf(o, h) * jacobian;
        }
        value += b.albedo * ((1.0f - t) * dt * kInvPi * std::fabs(ci));
        pdf->lobe[3] = p.diffuse_transmit * cosine_hemisphere_pdf(-ci);
    }
    return value;
}

BsdfSample principled_thin_sample(
    const BsdfParams& b, Vec3 o_in, float u_lobe, float u1, float u2) {
    if (o_in.z == 0.0f) return {};
    const float side = o_in.z > 0.0f ? 1.0f : -1.0f;
    const Vec3 o = o_in * side;
    const ThinLobes p = thin_lobes_of(b);
    Vec3 i;
    int lobe;
    if (u_lobe < p.spec_reflect) {
        lobe = 0;
        const MicrofacetDistribution dist{Microfacet::Ggx, b.alpha, b.alpha_v};
        i = reflect(o, dist.sample_visible(o, u1, u2));
    } else if (u_lobe < p.spec_reflect + p.spec_transmit) {
        lobe = 1;
        i = reflect(o, thin_transmission_ggx(b).sample_visible(o, u1, u2));
        i.z = -i.z;  // through the sheet, unrefracted
    } else if (u_lobe < p.spec_reflect + p.spec_transmit + p.diffuse_reflect) {
        lobe = 2;
        i = sample_cosine_hemisphere(u1, u2);
    } else {
        lobe = 3;
        i = -sample_cosine_hemisphere(u1, u2);
    }
    i = i * side;
    LobeDensities pdf;
    const Color f = principled_thin_eval(b, o_in, i, &pdf);
    return kept_sample(o_in, i, lobe, f, pdf);
}

}  // namespace

Color principled_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    LobeDensities lobes;
    const Color f = b.principled.thin ? principled_thin_eval(b, wo, wi, &lobes)
                                      : principled_full_eval(b, wo, wi, &lobes);
    *pdf = lobes.total();
    return f;
}

BsdfSample principled_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2) {
    return b.principled.thin ? principled_thin_sample(b, wo, u_lobe, u1, u2)
                             : principled_full_sample(b, wo, u_lobe, u1, u2);
}

void principled_alphas(float roughness, float anisotropic, float* alpha_u, float* alpha_v) {
    const float r2 = roughness * roughness, aspect = std::sqrt(1.0f - 0.9f * anisotropic);
    *alpha_u = std::max(0.001f, r2 / aspect);
    *alpha_v = std::max(0.001f, r2 * aspect);
}

float principled_eta_of_specular(float specular) {
    return 2.0f / (1.0f - std::sqrt(0.08f * specular)) - 1.0f;
}

}  // namespace wavetrace
