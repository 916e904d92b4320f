// The shadow rays that the light_sample kernel makes, in the order of its queue.
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Shadow rays start at t = 0; their media are those of their path (a vertex that samples
// lights never transmits, so the continuation leaves the path's media as they were). The
// vectors are rows, which light_sample's SIMD kernel writes a vector at a time.
#define WAVETRACE_SHADOW_FIELDS(F)                                                            \
    WAVETRACE_XYZ_FIELD(F, origin, "shadow ray origin, offset off the surface")               \
    WAVETRACE_XYZ_FIELD(F, dir, "unit direction to the light sample")                         \
    F(float, tmax, "just short of the light")                                                 \
    WAVETRACE_XYZ_FIELD(F, contribution, "beta f |cos| Le / p_light: unweighted, unoccluded") \
    F(float, pdf_light, "density of the light sample's direction")                            \
    F(float, pdf_bsdf, "density with which the BSDF would have sampled it")                   \
    F(uint32_t, path, "entry of the path (and ray) queue it belongs to")

WAVETRACE_SOA(ShadowQueue, WAVETRACE_SHADOW_FIELDS);

inline Ray shadow_ray_at(const ShadowQueue& q, size_t i) {
    return Ray{WAVETRACE_XYZ_AT(q, origin, i), WAVETRACE_XYZ_AT(q, dir, i), 0.0f, q.tmax[i]};
}

// One entry, with its vectors whole.
struct ShadowRay {
    Point3 origin;
    Vec3 dir;
    float tmax;
    Color contribution;
    float pdf_light, pdf_bsdf;
    uint32_t path;
};

inline void store_shadow_ray(ShadowQueue& q, size_t i, const ShadowRay& r) {
    q.store(
        i, {r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.tmax, r.contribution.x,
            r.contribution.y, r.contribution.z, r.pdf_light, r.pdf_bsdf, r.path});
}

}  // namespace wavetrace
