#include "bsdfs/conductor.h"

#include <cmath>

#include "bsdfs/fresnel.h"
#include "bsdfs/microfacet.h"

namespace wavetrace {
namespace {

// o and i on o's side mirrored above the surface: f cos and pdf for o.z > 0, i.z > 0.
Color eval_conductor_upper(const BsdfParams& b, Vec3 o, Vec3 i, float* pdf) {
    const MicrofacetDistribution md = microfacet_of(b);
    const Vec3 h = normalize(o + i);
    const float d = md.d(h);
    *pdf = md.g1(o) * d / (4.0f * o.z);
    const float cos_oh = dot(o, h);
    return b.albedo * fresnel_conductor(cos_oh, b.conductor_eta, b.conductor_k) *
           (d * md.g2(o, i) / (4.0f * o.z));
}

}  // namespace

Color conductor_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    *pdf = 0.0f;
    if (b.is_delta() || !(wo.z * wi.z > 0.0f)) return {};
    const float side = wo.z < 0.0f ? -1.0f : 1.0f;
    const Color f =
        eval_conductor_upper(b, {wo.x, wo.y, wo.z * side}, {wi.x, wi.y, wi.z * side}, pdf);
    if (!(*pdf > 0.0f)) {
        *pdf = 0.0f;
        return {};
    }
    return f;
}

BsdfSample conductor_sample(const BsdfParams& b, Vec3 wo, float u1, float u2) {
    BsdfSample s;
    if (wo.z == 0.0f) return s;
    const float side = wo.z < 0.0f ? -1.0f : 1.0f;
    if (b.is_delta()) {
        s.wi = {-wo.x, -wo.y, wo.z};
        s.weight = b.albedo * fresnel_conductor(std::fabs(wo.z), b.conductor_eta, b.conductor_k);
        s.delta = s.valid = true;
        return s;
    }
    const Vec3 o{wo.x, wo.y, wo.z * side};
    const Vec3 m = microfacet_of(b).sample_visible(o, u1, u2);
    const Vec3 i = 2.0f * dot(o, m) * m - o;
    if (!(i.z > 0.0f)) return s;  // reflected below the surface: lost
    // The value and density from (o, i) as eval computes them, so that weight = eval / pdf.
    const Color f = eval_conductor_upper(b, o, i, &s.pdf);
    if (!(s.pdf > 0.0f)) return s;
    s.wi = {i.x, i.y, i.z * side};
    s.weight = f / s.pdf;
    s.valid = true;
    return s;
}

}  // namespace wavetrace
