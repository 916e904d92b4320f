#include "bsdfs/microfacet.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/beckmann-inl.h"
#include "bsdfs/ggx-inl.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
namespace {

// The squared roughness along w's azimuth times sin^2 theta: au^2 wx^2 + av^2 wy^2.
double projected_roughness2(const MicrofacetDistribution& d, Vec3 w) {
    const double x = double(d.alpha_u) * w.x, y = double(d.alpha_v) * w.y;
    return x * x + y * y;
}

}  // namespace

float MicrofacetDistribution::d(Vec3 m) const {
    if (kind == Microfacet::Beckmann)
        return lanes::BeckmannD<lanes::OneLane>(lanes::to_lanes(m), alpha_u, alpha_v);
    if (m.z <= 0.0f) return 0.0f;
    const double z2 = double(m.z) * m.z;
    const double xu = m.x / double(alpha_u), yv = m.y / double(alpha_v);
    const double e = xu * xu + yv * yv;  // tan^2 theta_m / alpha^2 along m's azimuth, times z2
    const double norm = kPi * double(alpha_u) * alpha_v;
    const double t = e + z2;
    return static_cast<float>(1.0 / (norm * t * t));
}

float MicrofacetDistribution::lambda(Vec3 w) const {
    if (kind == Microfacet::Beckmann)
        return lanes::BeckmannLambda<lanes::OneLane>(lanes::to_lanes(w), alpha_u, alpha_v);
    const double z2 = double(w.z) * w.z;
    const double r2 = projected_roughness2(*this, w);  // 1 / a^2 = r2 / z2
    if (r2 <= 0.0) return 0.0f;
    if (z2 <= 0.0) return kInfinity;
    return static_cast<float>(0.5 * (std::sqrt(1.0 + r2 / z2) - 1.0));
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
    const auto o = lanes::to_lanes(wo);
    return lanes::to_vec3(
        kind == Microfacet::Ggx
            ? lanes::GgxVisibleNormal<lanes::OneLane>(o, alpha_u, alpha_v, u1, u2)
            : lanes::BeckmannVisibleNormal<lanes::OneLane>(o, alpha_u, alpha_v, u1, u2));
}

}  // namespace wavetrace
