#include "bsdfs/metallic_roughness.h"

#include <algorithm>
#include <cmath>

#include "bsdfs/fresnel.h"
#include "bsdfs/glossy-inl.h"
#include "bsdfs/metallic_roughness-inl.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;

namespace {

// The lanes' view of b, with its coat's own normal (LaneBsdf leaves every coat along the
// shading normal, as lane vertices' are).
lanes::MetallicRoughnessLanes<OneLane> one_lane(const BsdfParams& b) {
    lanes::MetallicRoughnessLanes<OneLane> mr = lanes::to_lanes(b).as_metallic_roughness();
    mr.coat_n = lanes::to_lanes(b.coat_normal_or_z());
    return mr;
}

}  // namespace

Color metallic_roughness_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf) {
    return lanes::to_vec3(
        lanes::MetallicRoughnessEval(one_lane(b), lanes::to_lanes(wo), lanes::to_lanes(wi), pdf));
}

float coat_emission_weight(float clearcoat, float oc) {
    lanes::MetallicRoughnessLanes<OneLane> mr{};
    mr.clearcoat = clearcoat;
    return 1.0f - clearcoat * lanes::CoatFresnel(mr, oc);
}

BsdfSample metallic_roughness_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1,
                                     float u2) {
    BsdfSample s;
    if (wo.z == 0.0f || (b.one_sided && wo.z < 0.0f)) return s;
    const float side = wo.z < 0.0f ? -1.0f : 1.0f;
    const lanes::MetallicRoughnessLanes<OneLane> mr = lanes::SeenFrom(one_lane(b), side);
    const Vec3 o{wo.x, wo.y, wo.z * side};
    const lanes::MetallicRoughnessLobes<OneLane> p =
        lanes::ChooseMetallicRoughnessLobes(mr, lanes::to_lanes(o));
    const bool coat = u_lobe < p.coat, specular = !coat && u_lobe < p.coat + p.specular;
    const bool diffuse = !coat && !specular && u_lobe < p.coat + p.specular + p.diffuse;
    const bool transmission = !coat && !specular && !diffuse && p.transmission > 0.0f;
    const float f0 = mr.f0, m = b.metallic;
    const float sn = schlick_weight(o.z), fd = f0 + (1.0f - f0) * sn;
    const Vec3 nc = lanes::to_vec3(mr.coat_n);
    const float oc = dot(o, nc);
    const float fc = lanes::CoatFresnel(mr, oc), base = 1.0f - b.clearcoat * fc;
    // A smooth coat about a normal of its own: its mirror direction, of weight k Fc / p.coat.
    const bool coat_apart = !b.coat_along_normal();
    if (coat && b.clearcoat_alpha == 0.0f && coat_apart) {
        const Vec3 i = 2.0f * oc * nc - o;
        if (!(i.z > 0.0f)) return s;  // below the surface: lost
        s.wi = {i.x, i.y, i.z * side};
        s.weight = Color(b.clearcoat * fc / p.coat);
        s.delta = s.valid = true;
        return s;
    }
    // Smooth lobes: every delta reflection (a smooth specular lobe, a smooth coat along the
    // shading normal) shares the mirror direction, so its weight is their summed value over
    // their summed probability.
    if ((specular && b.alpha == 0.0f) || (coat && b.clearcoat_alpha == 0.0f)) {
        Color value(0.0f);
        float prob = 0.0f;
        if (b.alpha == 0.0f) {
            const Color fm = b.albedo + (Color(1.0f) - b.albedo) * sn;
            value += (Color((1.0f - m) * fd) + fm * m) * base;
            prob += p.specular;
        }
        if (b.clearcoat_alpha == 0.0f && !coat_apart) {
            value += Color(p.coat > 0.0f ? b.clearcoat * fc : 0.0f);
            prob += p.coat;
        }
        s.wi = {-wo.x, -wo.y, wo.z};
        s.weight = value / prob;
        s.delta = s.valid = true;
        return s;
    }
    if (transmission && b.alpha == 0.0f) {
        s.wi = -wo;
        s.weight = b.albedo * (base * (1.0f - m) * b.transmission * (1.0f - fd) / p.transmission);
        s.delta = s.valid = s.transmitted = true;
        return s;
    }
    const lanes::MetallicRoughnessSampleResult<OneLane> r =
        lanes::MetallicRoughnessSampleUpper(mr, p, lanes::to_lanes(o), u_lobe, u1, u2);
    if (!r.valid) return s;
    s.wi = {r.wi.x, r.wi.y, r.wi.z * side};
    s.weight = lanes::to_vec3(r.weight);
    s.pdf = r.pdf;
    s.transmitted = r.transmitted;
    s.valid = true;
    return s;
}

}  // namespace wavetrace
