// The shadow rays that the light_sample kernel makes, in the order of its queue.
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Shadow rays start at t = 0; their media are those of their path (a vertex that samples
// lights never transmits, so the continuation leaves the path's media as they were).
#define WAVETRACE_SHADOW_FIELDS(F)                                              \
    F(Point3, origin, "shadow ray origin, offset off the surface")              \
    F(Vec3, dir, "unit direction to the light sample")                          \
    F(float, tmax, "just short of the light")                                   \
    F(Color, contribution, "beta f |cos| Le / p_light: unweighted, unoccluded") \
    F(float, pdf_light, "density of the light sample's direction")              \
    F(float, pdf_bsdf, "density with which the BSDF would have sampled it")     \
    F(uint32_t, path, "entry of the path (and ray) queue it belongs to")

WAVETRACE_SOA(ShadowQueue, WAVETRACE_SHADOW_FIELDS);

inline Ray shadow_ray_at(const ShadowQueue& q, size_t i) {
    return Ray{q.origin[i], q.dir[i], 0.0f, q.tmax[i]};
}

}  // namespace wavetrace
