#include "bsdfs/thin_dielectric.h"

#include <cmath>

#include "bsdfs/fresnel.h"

namespace wavetrace {

float thin_dielectric_reflectance(float cos_i, float eta) {
    const float r = fresnel_dielectric(cos_i, eta);
    if (r >= 1.0f) return 1.0f;
    const float t = 1.0f - r;
    return r + t * t * r / (1.0f - r * r);
}

BsdfSample thin_dielectric_sample(const BsdfParams& b, Vec3 wo, float u_lobe) {
    BsdfSample s;
    if (wo.z == 0.0f) return s;
    s.delta = s.valid = true;
    s.weight = Color(1.0f);
    if (u_lobe < thin_dielectric_reflectance(std::fabs(wo.z), b.eta)) {
        s.wi = {-wo.x, -wo.y, wo.z};
    } else {
        s.wi = -wo;
        s.transmitted = true;
    }
    return s;
}

}  // namespace wavetrace
