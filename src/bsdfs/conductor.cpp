#include "bsdfs/conductor.h"

#include "bsdfs/conductor-inl.h"

namespace wavetrace {
namespace {

namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;

lanes::RoughConductor<OneLane> rough_conductor(const BsdfParams& b) {
    return {lanes::to_lanes(b.albedo), lanes::to_lanes(b.conductor_eta),
            lanes::to_lanes(b.conductor_k), lanes::to_lanes(microfacet_of(b))};
}

}  // namespace

Color conductor_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    *pdf = 0.0f;
    if (b.is_delta()) return {};
    return lanes::to_vec3(lanes::RoughConductorEval(rough_conductor(b), lanes::to_lanes(wo),
                                                    lanes::to_lanes(wi), pdf));
}

BsdfSample conductor_sample(const BsdfParams& b, Vec3 wo, float u1, float u2) {
    BsdfSample s;
    if (wo.z == 0.0f) return s;
    const lanes::ReflectionSample<OneLane> r =
        lanes::RoughConductorSample(rough_conductor(b), lanes::to_lanes(wo), u1, u2);
    if (!r.valid) return s;
    s.wi = lanes::to_vec3(r.wi);
    s.weight = lanes::to_vec3(r.weight);
    s.pdf = r.pdf;
    s.valid = true;
    return s;
}

}  // namespace wavetrace
