#include "bsdfs/fresnel.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/conductor-inl.h"
#include "bsdfs/metal-inl.h"

namespace wavetrace {

float fresnel_dielectric(float cos_i, float eta) {
    float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
    if (sin2_t >= 1.0f) return 1.0f;  // total internal reflection
    float cos_t = std::sqrt(1.0f - sin2_t);
    float r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    float r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return 0.5f * (r_par * r_par + r_perp * r_perp);
}

Color fresnel_conductor(float cos_i, Color eta, Color k) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::to_vec3(
        lanes::FresnelConductor<lanes::OneLane>(cos_i, lanes::to_lanes(eta), lanes::to_lanes(k)));
}

float schlick_weight(float cos_theta) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::SchlickWeight<lanes::OneLane>(cos_theta);
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
