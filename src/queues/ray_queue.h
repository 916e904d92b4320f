// Rays to trace, one per live path, compacted after every bounce; and their closest hits,
// entry for entry.
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

#define WAVETRACE_RAY_QUEUE_FIELDS(F)                    \
    F(Point3, origin, "ray origin")                      \
    F(Vec3, dir, "ray direction (not necessarily unit)") \
    F(float, tmin, "start of the valid interval")        \
    F(uint32_t, path, "path slot in the wave")

WAVETRACE_SOA(RayQueue, WAVETRACE_RAY_QUEUE_FIELDS);

#define WAVETRACE_HIT_QUEUE_FIELDS(F)                        \
    F(float, t, "hit distance in units of |dir|; inf: miss") \
    F(PrimRef, prim, "primitive hit (invalid: miss)")        \
    F(float, u, "surface parameter")                         \
    F(float, v, "surface parameter")

WAVETRACE_SOA(HitQueue, WAVETRACE_HIT_QUEUE_FIELDS);

}  // namespace wavetrace
