#include "bsdfs/rough_dielectric.h"

#include <cmath>

#include "bsdfs/fresnel.h"
#include "microfacets/microfacet.h"

namespace wavetrace {
namespace {

// wo.z > 0 (both directions mirrored so); eta = index of the side below over the side above.
// f cos and pdf for wi on either side.
Color eval_dielectric_upper(const BsdfParams& b, Vec3 o, Vec3 i, float eta, float* pdf) {
    *pdf = 0.0f;
    const MicrofacetDistribution md = microfacet_of(b);
    const bool reflect = i.z > 0.0f;
    Vec3 h = reflect ? o + i : -(eta * i + o);
    if (!(length_squared(h) > 0.0f)) return {};
    h = normalize(h);
    if (h.z < 0.0f) h = -h;
    const float cos_oh = dot(o, h), cos_ih = dot(i, h);
    // The microfacet must face wo, and wi must leave on its side (reflection) or the other.
    if (!(cos_oh > 0.0f) || (reflect ? !(cos_ih > 0.0f) : !(cos_ih < 0.0f))) return {};
    const float f = fresnel_dielectric(cos_oh, eta);
    const float d = md.d(h), g2 = md.g2(o, i);
    const float visible = md.g1(o) * cos_oh * d / o.z;  // D_wo(h)
    if (reflect) {
        *pdf = f * visible / (4.0f * cos_oh);
        return Color(f * d * g2 / (4.0f * o.z));
    }
    const float denom = eta * cos_ih + cos_oh;
    const float jacobian = eta * eta * std::fabs(cos_ih) / (denom * denom);
    *pdf = (1.0f - f) * visible * jacobian;
    return Color(std::fabs(cos_ih) * cos_oh * (1.0f - f) * d * g2 / (o.z * denom * denom));
}

}  // namespace

Color rough_dielectric_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    *pdf = 0.0f;
    if (wo.z == 0.0f || wi.z == 0.0f) return {};
    const float side = wo.z < 0.0f ? -1.0f : 1.0f;
    const float eta = wo.z > 0.0f ? b.eta : 1.0f / b.eta;
    const Color f =
        eval_dielectric_upper(b, {wo.x, wo.y, wo.z * side}, {wi.x, wi.y, wi.z * side}, eta, pdf);
    if (!(*pdf > 0.0f)) {
        *pdf = 0.0f;
        return {};
    }
    return f;
}

BsdfSample rough_dielectric_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2) {
    BsdfSample s;
    if (wo.z == 0.0f) return s;
    const float side = wo.z < 0.0f ? -1.0f : 1.0f;
    const float eta = wo.z > 0.0f ? b.eta : 1.0f / b.eta;
    const Vec3 o{wo.x, wo.y, wo.z * side};
    const Vec3 m = microfacet_of(b).sample_visible(o, u1, u2);
    const float cos_om = dot(o, m);
    if (!(cos_om > 0.0f)) return s;
    const float f = fresnel_dielectric(cos_om, eta);
    Vec3 i;
    if (u_lobe < f) {
        i = 2.0f * cos_om * m - o;
        if (!(i.z > 0.0f)) return s;
    } else {
        if (!refract(o, m, eta, &i)) return s;  // total internal reflection: f = 1, not reached
        if (!(i.z < 0.0f)) return s;
        s.transmitted = true;
    }
    // The value and density from (o, i) as eval computes them, so that weight = eval / pdf.
    const Color value = eval_dielectric_upper(b, o, i, eta, &s.pdf);
    if (!(s.pdf > 0.0f)) return s;
    s.wi = {i.x, i.y, i.z * side};
    s.weight = value / s.pdf;
    s.valid = true;
    return s;
}

}  // namespace wavetrace
