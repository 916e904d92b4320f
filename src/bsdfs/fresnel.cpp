#include "bsdfs/fresnel.h"

#include "bsdfs/conductor-inl.h"
#include "bsdfs/dielectric-inl.h"
#include "bsdfs/metal-inl.h"

namespace wavetrace {

float fresnel_dielectric(float cos_i, float eta) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::FresnelDielectric<lanes::OneLane>(cos_i, eta);
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
    namespace lanes = HWY_NAMESPACE;
    lanes::V3<float> refracted;
    if (!lanes::Refract<lanes::OneLane>(lanes::to_lanes(o), lanes::to_lanes(m), eta, &refracted))
        return false;
    *i = lanes::to_vec3(refracted);
    return true;
}

}  // namespace wavetrace
