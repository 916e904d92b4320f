#include "bsdfs/rough_dielectric.h"

#include "bsdfs/dielectric-inl.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;

Color rough_dielectric_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    return Color(lanes::RoughDielectricEval<OneLane>(
        lanes::to_lanes(microfacet_of(b)), b.eta, lanes::to_lanes(wo), lanes::to_lanes(wi), pdf));
}

BsdfSample rough_dielectric_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2) {
    const lanes::DielectricSample<OneLane> r = lanes::RoughDielectricSample<OneLane>(
        lanes::to_lanes(microfacet_of(b)), b.eta, lanes::to_lanes(wo), u_lobe, u1, u2);
    BsdfSample s;
    if (!r.valid) return s;
    s.wi = lanes::to_vec3(r.wi);
    s.weight = Color(r.weight);
    s.pdf = r.pdf;
    s.transmitted = r.transmitted;
    s.valid = true;
    return s;
}

}  // namespace wavetrace
