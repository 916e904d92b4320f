#include "microfacets/microfacet.h"

#include "microfacets/microfacet-inl.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;

float MicrofacetDistribution::d(Vec3 m) const {
    return lanes::MicrofacetD(lanes::to_lanes(*this), lanes::to_lanes(m));
}

float MicrofacetDistribution::lambda(Vec3 w) const {
    return lanes::MicrofacetLambda(lanes::to_lanes(*this), lanes::to_lanes(w));
}

float MicrofacetDistribution::g1(Vec3 w) const {
    return 1.0f / (1.0f + lambda(w));
}

float MicrofacetDistribution::g2(Vec3 wo, Vec3 wi) const {
    return 1.0f / (1.0f + lambda(wo) + lambda(wi));
}

float MicrofacetDistribution::visible_pdf(Vec3 wo, Vec3 m) const {
    const float cos_om = dot(wo, m);
    if (!(cos_om > 0.0f) || !(wo.z > 0.0f)) return 0.0f;
    return g1(wo) * cos_om * d(m) / wo.z;
}

Vec3 MicrofacetDistribution::sample_visible(Vec3 wo, float u1, float u2) const {
    return lanes::to_vec3(
        lanes::MicrofacetVisibleNormal(lanes::to_lanes(*this), lanes::to_lanes(wo), u1, u2));
}

}  // namespace wavetrace
