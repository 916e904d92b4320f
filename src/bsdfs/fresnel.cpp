#include "bsdfs/fresnel.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/ggx-inl.h"

namespace wavetrace {

float fresnel_dielectric(float cos_i, float eta) {
    float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
    float cos_t = std::sqrt(1.0f - sin2_t);
    float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

namespace {

// One channel. With n^2 = (eta + i k)^2 - sin^2 theta = a2b2 e^(i phi) written as (a + i b)^2:
// R_s = (a2b2 - 2 a c + c^2) / (a2b2 + 2 a c + c^2),
// R_p = R_s (a2b2 c^2 - 2 a c s^2 + s^4) / (a2b2 c^2 + 2 a c s^2 + s^4), c = cos, s = sin.
// In double: at k = 6, a2b2 ~ 40 and the differences lose a float's digits near normal incidence.
float conductor_channel(double c, double eta, double k) {
    const double c2 = c * c, s2 = 1.0 - c2;
    const double t0 = eta * eta - k * k - s2;
    const double a2b2 = std::sqrt(t0 * t0 + 4.0 * eta * eta * k * k);
    const double a = std::sqrt(std::max(0.0, 0.5 * (a2b2 + t0)));
    if (!(a2b2 + 2.0 * a * c + c2 > 0.0)) return 1.0f;  // grazing onto eta = 1, k = 0
    const double rs = (a2b2 - 2.0 * a * c + c2) / (a2b2 + 2.0 * a * c + c2);
    const double t1 = a2b2 * c2 + s2 * s2, t2 = 2.0 * a * c * s2;
    const double rp = rs * (t1 - t2) / (t1 + t2);
    return static_cast<float>(0.5 * (rs + rp));
}

}  // namespace

Color fresnel_conductor(float cos_i, Color eta, Color k) {
    const double c = std::clamp(static_cast<double>(cos_i), 0.0, 1.0);
    return {conductor_channel(c, eta.x, k.x), conductor_channel(c, eta.y, k.y),
            conductor_channel(c, eta.z, k.z)};
}

float schlick_weight(float cos_theta) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::Schlick<lanes::OneLane>(lanes::to_lanes(Color(0.0f)), cos_theta).x;
}

bool refract(Vec3 o, Vec3 m, float eta, Vec3* i) {
    const float cos_om = dot(o, m);
    const float sin2_t = (1.0f - cos_om * cos_om) / (eta * eta);
    if (sin2_t >= 1.0f) return false;
    const float cos_t = std::sqrt(1.0f - sin2_t);
    *i = normalize(-o / eta + (cos_om / eta - cos_t) * m);
    return true;
}

}  // namespace wavetrace
