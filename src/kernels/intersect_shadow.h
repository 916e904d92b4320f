#pragma once

#include <algorithm>
#include <span>

#include "accel/intersector.h"
#include "kernels/intersect.h"
#include "kernels/wave.h"
#include "shading/trace.h"

namespace wavetrace {

// Whether shadow entries [first, first + count) leave one primitive (their paths' hits in
// `origins`): coherent enough to go as a packet.
inline bool leave_one_primitive(const HitQueue& origins,
                                const ShadowQueue& shadows,
                                size_t first,
                                size_t count) {
    const PrimRef p = origins.prim[shadows.path[first]];
    for (size_t k = 1; k < count; ++k)
        if (origins.prim[shadows.path[first + k]] != p) return false;
    return true;
}

// Transmittance along shadows[i] (0 if blocked), in its media; returns the rays
// traced. `origins`, where given: the hits the rays leave from, those of the camera rays, in
// pixel tiles. Eight consecutive rays that leave one primitive (a tile on one wall) are then
// traced as a packet where the intersector has them: coherent enough that the packet pays. Rays
// from a tile spread over a mesh's many small triangles part ways in the tree, and a packet would
// visit what only some of them need (the dragon: 3% slower as packets).
template <Intersector Tracer>
uint64_t intersect_shadow(const Tracer& tracer,
                          const WaveInputs& in,
                          const ShadowQueue& shadows,
                          size_t begin,
                          size_t end,
                          std::span<Color> transmittance,
                          const HitQueue* origins = nullptr) {
    if (!in.shadows_walk) {  // a blocker or not: no medium stack to read
        if constexpr (StreamIntersector<Tracer> && PacketIntersector<Tracer>) {
            constexpr size_t kPacket = 8;
            Ray batch[kRayBatch];
            bool blocked[kRayBatch];
            for (size_t b = begin; b < end; b += kRayBatch) {
                const size_t m = std::min(kRayBatch, end - b);
                for (size_t k = 0; k < m; ++k) batch[k] = shadow_ray_at(shadows, b + k);
                if (!origins) {
                    tracer.occluded_each(std::span<const Ray>(batch, m),
                                         std::span<bool>(blocked, m));
                } else {
                    for (size_t g = 0; g < m; g += kPacket) {
                        const size_t gm = std::min(kPacket, m - g);
                        const std::span<const Ray> group(batch + g, gm);
                        const std::span<bool> out(blocked + g, gm);
                        if (leave_one_primitive(*origins, shadows, b + g, gm))
                            tracer.occluded_packet(group, out);
                        else
                            tracer.occluded_each(group, out);
                    }
                }
                for (size_t k = 0; k < m; ++k) transmittance[b + k] = Color(blocked[k] ? 0.0f : 1.0f);
            }
        } else {
            for (size_t i = begin; i < end; ++i)
                transmittance[i] = Color(tracer.occluded(shadow_ray_at(shadows, i)) ? 0.0f : 1.0f);
        }
        return end - begin;
    }
    // Through media and the surfaces shadow rays pass: the occlusion test that says what it
    // stopped at, 64 rays to a call (at the first bounce, eight that leave one primitive as a
    // packet first: one it finds unblocked meets no boundary either); only rays stopped by a
    // surface they pass walk on.
    uint64_t rays = 0;
    if constexpr (StreamIntersector<Tracer> && PacketIntersector<Tracer> &&
                  AnyHitIntersector<Tracer>) {
        constexpr size_t kPacket = 8;
        Ray batch[kRayBatch];
        Hit any[kRayBatch];
        bool blocked[kRayBatch];
        for (size_t b = begin; b < end; b += kRayBatch) {
            const size_t m = std::min(kRayBatch, end - b);
            for (size_t k = 0; k < m; ++k) batch[k] = shadow_ray_at(shadows, b + k);
            std::fill(blocked, blocked + m, true);  // unknown: take the any-hit test
            if (origins)
                for (size_t g = 0; g + kPacket <= m; g += kPacket) {
                    if (leave_one_primitive(*origins, shadows, b + g, kPacket)) {
                        tracer.occluded_packet(std::span<const Ray>(batch + g, kPacket),
                                               std::span<bool>(blocked + g, kPacket));
                        rays += kPacket;
                    }
                }
            // The rays left (all but those a packet found unblocked), in one stream.
            Ray left[kRayBatch];
            size_t n_left = 0;
            for (size_t k = 0; k < m; ++k)
                if (blocked[k]) left[n_left++] = batch[k];
            tracer.any_hit_each(std::span<const Ray>(left, n_left), std::span<Hit>(any, n_left));
            rays += n_left;
            size_t j = 0;
            for (size_t k = 0; k < m; ++k) {
                const size_t i = b + k;
                const MediumStack media = shadows.media[i].unpack();
                const Hit found = blocked[k] ? any[j++] : Hit{};
                const std::optional<Color> tr =
                    transmittance_after_any_hit(in.scene, batch[k], media, found);
                transmittance[i] =
                    tr ? *tr : transmittance_walk(in.scene, tracer, batch[k], media, &rays);
            }
        }
        return rays;
    }
    for (size_t i = begin; i < end; ++i)
        transmittance[i] = wavetrace::transmittance(in.scene, tracer, shadow_ray_at(shadows, i),
                                                    shadows.media[i].unpack(), true,
                                                    &rays);
    return rays;
}

}  // namespace wavetrace
