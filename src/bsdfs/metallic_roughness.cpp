#include "bsdfs/metallic_roughness.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/fresnel.h"
#include "bsdfs/ggx-inl.h"
#include "bsdfs/microfacet.h"
#include "sampling/warp.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;
namespace {

// The clearcoat's Fresnel at the view direction (0 without a clearcoat).
float coat_fresnel(const BsdfParams& b, Vec3 o) {
    return b.clearcoat > 0.0f ? 0.04f + 0.96f * schlick_weight(o.z) : 0.0f;
}

// The probabilities of the lobes for o (o.z > 0), in proportion to their shares of the light
// at V.h = N.V; they sum to 1, or are all 0 when nothing is reflected.
struct LobeChoice {
    float coat = 0.0f, specular = 0.0f, diffuse = 0.0f, transmission = 0.0f;
};
LobeChoice choose_lobes(const BsdfParams& b, Vec3 o) {
    const float s = schlick_weight(o.z), f0 = schlick_f0(b.eta);
    const float fd = f0 + (1.0f - f0) * s, fm = mean(b.albedo + (Color(1.0f) - b.albedo) * s);
    const float fc = coat_fresnel(b, o), base = 1.0f - b.clearcoat * fc;
    const float m = b.metallic, c = mean(b.albedo);
    LobeChoice p;
    p.coat = b.clearcoat * fc;
    // At least 2% of the base for the specular lobe: a black metal still reflects at grazing
    // half vectors, and a lobe with f > 0 must have a density there.
    p.specular = base * std::max((1.0f - m) * fd + m * fm, 0.02f);
    p.diffuse = base * (1.0f - m) * (1.0f - b.transmission) * (1.0f - fd) * c;
    p.transmission = base * (1.0f - m) * b.transmission * (1.0f - fd) * c;
    const float sum = p.coat + p.specular + p.diffuse + p.transmission;
    if (!(sum > 0.0f)) return {};
    p.coat /= sum;
    p.specular /= sum;
    p.diffuse /= sum;
    p.transmission /= sum;
    return p;
}

// f cos_i of the lobes that are not deltas, and their density weighted by the lobe
// probabilities, for o above the surface (o.z > 0) and i on either side.
Color eval_metallic_upper(const BsdfParams& b, const LobeChoice& p, Vec3 o, Vec3 i, float* pdf) {
    *pdf = 0.0f;
    const float f0 = schlick_f0(b.eta), m = b.metallic;
    const float fc = coat_fresnel(b, o), base = 1.0f - b.clearcoat * fc;
    const MicrofacetDistribution md{Microfacet::Ggx, b.alpha, b.alpha};
    Color f(0.0f);
    if (i.z > 0.0f) {
        const Vec3 h = normalize(o + i);
        const float s = schlick_weight(dot(o, h));
        const float fd = f0 + (1.0f - f0) * s;
        const Color fm = b.albedo + (Color(1.0f) - b.albedo) * s;
        f += b.albedo * (base * (1.0f - m) * (1.0f - b.transmission) * (1.0f - fd) * i.z * kInvPi);
        *pdf += p.diffuse * i.z * kInvPi;
        if (b.alpha > 0.0f) {
            // D G1(o) G1(i) / (4 o.z i.z) times i.z; the visible normals' density of h times the
            // reflection's Jacobian 1 / (4 o.h) is G1(o) D / (4 o.z).
            const float d = md.d(h), g1_o = md.g1(o);
            const float spec = d * g1_o * md.g1(i) / (4.0f * o.z);
            f += (Color((1.0f - m) * fd) + fm * m) * (base * spec);
            *pdf += p.specular * g1_o * d / (4.0f * o.z);
        }
        if (b.clearcoat > 0.0f && b.clearcoat_alpha > 0.0f) {
            const MicrofacetDistribution mc{Microfacet::Ggx, b.clearcoat_alpha,
                                            b.clearcoat_alpha};
            const float d = mc.d(h), g1_o = mc.g1(o);
            f += Color(b.clearcoat * fc * d * g1_o * mc.g1(i) / (4.0f * o.z));
            *pdf += p.coat * g1_o * d / (4.0f * o.z);
        }
    } else if (i.z < 0.0f && b.alpha > 0.0f && b.transmission > 0.0f) {
        // The thin-walled BTDF: the specular lobe with i mirrored through the surface.
        const Vec3 im{i.x, i.y, -i.z};
        const Vec3 h = normalize(o + im);
        const float fd = f0 + (1.0f - f0) * schlick_weight(dot(o, h));
        const float d = md.d(h), g1_o = md.g1(o);
        const float spec = d * g1_o * md.g1(im) / (4.0f * o.z);
        f += b.albedo * (base * (1.0f - m) * b.transmission * (1.0f - fd) * spec);
        *pdf += p.transmission * g1_o * d / (4.0f * o.z);
    }
    if (!(*pdf > 0.0f)) {
        *pdf = 0.0f;
        return {};
    }
    return f;
}

}  // namespace

Color metallic_roughness_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    *pdf = 0.0f;
    if (wo.z == 0.0f || (b.one_sided && wo.z < 0.0f)) return {};
    const float side = wo.z < 0.0f ? -1.0f : 1.0f;
    const Vec3 o{wo.x, wo.y, wo.z * side}, i{wi.x, wi.y, wi.z * side};
    return eval_metallic_upper(b, choose_lobes(b, o), o, i, pdf);
}

BsdfSample metallic_roughness_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1,
                                     float u2) {
    BsdfSample s;
    if (wo.z == 0.0f || (b.one_sided && wo.z < 0.0f)) return s;
    const float side = wo.z < 0.0f ? -1.0f : 1.0f;
    const Vec3 o{wo.x, wo.y, wo.z * side};
    const LobeChoice p = choose_lobes(b, o);
    const bool coat = u_lobe < p.coat, specular = !coat && u_lobe < p.coat + p.specular;
    const bool diffuse = !coat && !specular && u_lobe < p.coat + p.specular + p.diffuse;
    const bool transmission = !coat && !specular && !diffuse && p.transmission > 0.0f;
    if (!coat && !specular && !diffuse && !transmission) return s;
    const float f0 = schlick_f0(b.eta), m = b.metallic;
    const float sn = schlick_weight(o.z), fd = f0 + (1.0f - f0) * sn;
    const float base = 1.0f - b.clearcoat * coat_fresnel(b, o);
    // Smooth lobes: every delta reflection (a smooth specular lobe, a smooth coat) shares the
    // mirror direction, so its weight is their summed value over their summed probability.
    if ((specular && b.alpha == 0.0f) || (coat && b.clearcoat_alpha == 0.0f)) {
        Color value(0.0f);
        float prob = 0.0f;
        if (b.alpha == 0.0f) {
            const Color fm = b.albedo + (Color(1.0f) - b.albedo) * sn;
            value += (Color((1.0f - m) * fd) + fm * m) * base;
            prob += p.specular;
        }
        if (b.clearcoat_alpha == 0.0f) {
            value += Color(p.coat > 0.0f ? b.clearcoat * coat_fresnel(b, o) : 0.0f);
            prob += p.coat;
        }
        s.wi = {-wo.x, -wo.y, wo.z};
        s.weight = value / prob;
        s.delta = s.valid = true;
        return s;
    }
    if (transmission && b.alpha == 0.0f) {
        s.wi = -wo;
        s.weight = b.albedo * (base * (1.0f - m) * b.transmission * (1.0f - fd) / p.transmission);
        s.delta = s.valid = s.transmitted = true;
        return s;
    }
    Vec3 i;
    if (diffuse) {
        i = sample_cosine_hemisphere(u1, u2);
    } else {
        const float alpha = coat ? b.clearcoat_alpha : b.alpha;
        const Vec3 n = MicrofacetDistribution{Microfacet::Ggx, alpha, alpha}.sample_visible(o, u1, u2);
        i = 2.0f * dot(o, n) * n - o;
        if (!(i.z > 0.0f)) return s;  // reflected below the surface: lost
        if (transmission) i.z = -i.z;
    }
    // The value and density from (o, i) as eval computes them, so that weight = eval / pdf.
    const Color f = eval_metallic_upper(b, p, o, i, &s.pdf);
    if (!(s.pdf > 0.0f)) return s;
    s.wi = {i.x, i.y, i.z * side};
    s.weight = f / s.pdf;
    s.transmitted = transmission;
    s.valid = true;
    return s;
}

}  // namespace wavetrace
