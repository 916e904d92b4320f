// Uniform numbers that belong to a ray's hit rather than to the path's sampler: pbrt-v4's
// stochastic alpha test and its mix material decide from a hash of the hit, so that the same
// ray meeting the same primitive decides the same way in both engines, both intersectors and
// any-hit and closest-hit walks, and the sampler's dimension layout does not change. For code
// compiled once, for the static target (sampler-inl.h is a per-target header).
#pragma once

#include <bit>
#include <cstdint>

#include "sampling/sampler-inl.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

// What a hit's number decides; each its own stream, so that decisions at one hit are
// independent of one another.
enum class HitDecision : uint64_t {
    Opacity = 0x9e3779b97f4a7c15ull,
    Blend = 0xd1b54a32d192ed03ull,
};

// A uniform number in [0, 1) from the ray (origin, direction), the primitive and the decision.
inline float hit_hash(const Ray& ray, PrimRef prim, HitDecision what) {
    using HWY_NAMESPACE::Mix64, HWY_NAMESPACE::OneLane;
    uint64_t h = Mix64<OneLane>(static_cast<uint64_t>(what) ^ prim.bits);
    for (float f : {ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z})
        h = Mix64<OneLane>(h ^ std::bit_cast<uint32_t>(f));
    return float(h >> 40) * 0x1p-24f;
}

}  // namespace wavetrace
