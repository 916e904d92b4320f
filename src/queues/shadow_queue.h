// The shadow rays that the light_sample kernel makes, in the order of its queue.
#pragma once

#include <cstdint>

#include "queues/packed_media.h"
#include "queues/soa.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Shadow rays start at t = 0, in their own media (shadow_media: a rough dielectric's light
// sample may leave through the other side of the surface, whichever side its path goes on
// to). The vectors are rows, which light_sample's SIMD kernel writes a vector at a time.
#define WAVETRACE_SHADOW_FIELDS(F)                                                            \
    WAVETRACE_XYZ_FIELD(F, origin, "shadow ray origin, offset off the surface")               \
    WAVETRACE_XYZ_FIELD(F, dir, "unit direction to the light sample")                         \
    F(float, tmax, "just short of the light")                                                 \
    WAVETRACE_XYZ_FIELD(F, contribution, "beta f |cos| Le / p_light: unweighted, unoccluded") \
    F(float, pdf_light, "density of the light sample's direction")                            \
    F(float, pdf_bsdf, "density with which the BSDF would have sampled it")                   \
    F(uint32_t, path, "entry of the path (and ray) queue it belongs to")                      \
    F(PackedMedia, media, "the media the ray starts in")

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
    PackedMedia media;
};

inline void store_shadow_ray(ShadowQueue& q, size_t i, const ShadowRay& r) {
    q.store(
        i, {r.origin.x, r.origin.y, r.origin.z, r.dir.x, r.dir.y, r.dir.z, r.tmax, r.contribution.x,
            r.contribution.y, r.contribution.z, r.pdf_light, r.pdf_bsdf, r.path, r.media});
}

}  // namespace wavetrace
