#include "bsdfs/microfacet.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/ggx-inl.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace {

constexpr double kInvSqrtPi = 0.56418958354775628695;

// The inverse error function in double: Giles' single-precision approximation ("Approximating
// the erfinv function", GPU Computing Gems, 2011) as the starting point, refined by two Newton
// steps on erf(x) - y (each doubles the correct digits).
double erfinv(double y) {
    y = std::clamp(y, -1.0 + 1e-16, 1.0 - 1e-16);
    double w = -std::log((1.0 - y) * (1.0 + y)), p;
    if (w < 5.0) {
        w -= 2.5;
        p = 2.81022636e-08;
        p = 3.43273939e-07 + p * w;
        p = -3.5233877e-06 + p * w;
        p = -4.39150654e-06 + p * w;
        p = 0.00021858087 + p * w;
        p = -0.00125372503 + p * w;
        p = -0.00417768164 + p * w;
        p = 0.246640727 + p * w;
        p = 1.50140941 + p * w;
    } else {
        w = std::sqrt(w) - 3.0;
        p = -0.000200214257;
        p = 0.000100950558 + p * w;
        p = 0.00134934322 + p * w;
        p = -0.00367342844 + p * w;
        p = 0.00573950773 + p * w;
        p = -0.0076224613 + p * w;
        p = 0.00943887047 + p * w;
        p = 1.00167406 + p * w;
        p = 2.83297682 + p * w;
    }
    double x = p * y;
    for (int i = 0; i < 2; ++i) x -= (std::erf(x) - y) / (2.0 * kInvSqrtPi * std::exp(-x * x));
    return x;
}

// The squared roughness along w's azimuth times sin^2 theta: au^2 wx^2 + av^2 wy^2.
double projected_roughness2(const MicrofacetDistribution& d, Vec3 w) {
    const double x = double(d.alpha_u) * w.x, y = double(d.alpha_v) * w.y;
    return x * x + y * y;
}

// The slopes of a visible normal of the unit-roughness Beckmann distribution seen from a
// direction of cosine cos_theta with the normal and azimuth 0. The visible slopes have density
// proportional to (cot theta - x) exp(-x^2 - y^2) for x < cot theta (Heitz & d'Eon 2014,
// §4): y is a normal deviate, and x inverts the CDF
//   C(x) = (1 + erf(x) + tan theta exp(-x^2) / sqrt(pi)) / (1 + erf(cot theta) + tan theta
//          exp(-cot^2 theta) / sqrt(pi)),
// increasing for x < cot theta with C'(x) proportional to exp(-x^2) (1 - x tan theta); solved
// by Newton's method on x itself (one erf and one exp a step; on b = erf(x) each step would
// need an erfinv), kept inside a bisection bracket, from x = erfinv(b) with b what C would be
// without its tan theta terms.
void beckmann_visible_slopes(double cos_theta, double u1, double u2, double* x, double* y) {
    *y = erfinv(2.0 * u2 - 1.0);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    if (sin_theta < 1e-6 * cos_theta) {  // normal incidence: the slopes' own distribution
        *x = erfinv(2.0 * u1 - 1.0);
        return;
    }
    const double tan_theta = sin_theta / cos_theta, cot_theta = cos_theta / sin_theta;
    const double erf_cot = std::erf(cot_theta);
    const double norm =
        1.0 / (1.0 + erf_cot + tan_theta * std::exp(-cot_theta * cot_theta) * kInvSqrtPi);
    // C(-9) < 1e-36: below any u1 a float holds but 0.
    double lo = -9.0, hi = cot_theta;
    double t = std::clamp(erfinv(-1.0 + (1.0 + erf_cot) * u1), lo, hi);
    for (int i = 0; i < 64; ++i) {
        const double g = std::exp(-t * t);
        const double value = norm * (1.0 + std::erf(t) + tan_theta * g * kInvSqrtPi) - u1;
        if (std::fabs(value) < 1e-12) break;
        (value > 0.0 ? hi : lo) = t;
        const double slope = norm * 2.0 * kInvSqrtPi * g * (1.0 - t * tan_theta);
        const double step = t - value / slope;
        t = step > lo && step < hi ? step : 0.5 * (lo + hi);
        if (hi - lo < 1e-15 * std::max(1.0, std::fabs(t))) break;
    }
    *x = t;
}

}  // namespace

float MicrofacetDistribution::d(Vec3 m) const {
    if (m.z <= 0.0f) return 0.0f;
    const double z2 = double(m.z) * m.z;
    const double xu = m.x / double(alpha_u), yv = m.y / double(alpha_v);
    const double e = xu * xu + yv * yv;  // tan^2 theta_m / alpha^2 along m's azimuth, times z2
    const double norm = kPi * double(alpha_u) * alpha_v;
    if (kind == Microfacet::Ggx) {
        const double t = e + z2;
        return static_cast<float>(1.0 / (norm * t * t));
    }
    return static_cast<float>(std::exp(-e / z2) / (norm * z2 * z2));
}

float MicrofacetDistribution::lambda(Vec3 w) const {
    const double z2 = double(w.z) * w.z;
    const double r2 = projected_roughness2(*this, w);  // 1 / a^2 = r2 / z2
    if (r2 <= 0.0) return 0.0f;
    if (z2 <= 0.0) return kInfinity;
    if (kind == Microfacet::Ggx) return static_cast<float>(0.5 * (std::sqrt(1.0 + r2 / z2) - 1.0));
    const double a = std::fabs(double(w.z)) / std::sqrt(r2);
    // (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)), with erfc for the difference at large a.
    return static_cast<float>(0.5 * (std::exp(-a * a) * kInvSqrtPi / a - std::erfc(a)));
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
    namespace lanes = HWY_NAMESPACE;
    if (kind == Microfacet::Ggx)
        return lanes::to_vec3(
            lanes::GgxVisibleNormal<lanes::OneLane>(lanes::to_lanes(wo), alpha_u, alpha_v, u1, u2));
    // Stretch to unit roughness; the slopes there, rotated to the stretched wo's azimuth;
    // unstretched slopes (x, y) are the normal (-x, -y, 1).
    const double sx = double(alpha_u) * wo.x, sy = double(alpha_v) * wo.y, sz = wo.z;
    const double len = std::sqrt(sx * sx + sy * sy + sz * sz);
    const double sin_theta = std::sqrt(sx * sx + sy * sy) / len;
    double x, y;
    beckmann_visible_slopes(sz / len, u1, u2, &x, &y);
    double cos_phi = 1.0, sin_phi = 0.0;
    if (sin_theta > 0.0) {
        cos_phi = sx / (len * sin_theta);
        sin_phi = sy / (len * sin_theta);
    }
    const double rx = (cos_phi * x - sin_phi * y) * alpha_u;
    const double ry = (sin_phi * x + cos_phi * y) * alpha_v;
    const double n = std::sqrt(rx * rx + ry * ry + 1.0);
    return {static_cast<float>(-rx / n), static_cast<float>(-ry / n), static_cast<float>(1.0 / n)};
}

}  // namespace wavetrace
