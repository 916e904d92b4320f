#pragma once

#include <algorithm>
#include <span>

#include "kernels/intersect.h"
#include "kernels/wave.h"
#include "scene/intersector.h"
#include "shading/trace.h"

namespace wavetrace {

// Transmittance along shadows[i] (0 if blocked), in the media of its path; returns the rays
// traced. `origins`, where given: the hits the rays leave from, those of the camera rays, in
// pixel tiles. Without media, eight consecutive rays that leave one primitive (a tile on one
// wall) are then traced as a packet where the intersector has them: coherent enough that the
// packet pays. Rays from a tile spread over a mesh's many small triangles part ways in the tree,
// and a packet would visit what only some of them need (the dragon: 3% slower as packets).
template <Intersector Tracer>
uint64_t intersect_shadow(const Tracer& tracer,
                          const WaveInputs& in,
                          const ShadowQueue& shadows,
                          const PathQueue& paths,
                          size_t begin,
                          size_t end,
                          std::span<float> transmittance,
                          const HitQueue* origins = nullptr) {
    if (in.scene.media.empty()) {  // a blocker or not: no medium stack to read
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
                        const PrimRef first = origins->prim[shadows.path[b + g]];
                        bool one_primitive = true;
                        for (size_t k = 1; k < gm; ++k)
                            one_primitive =
                                one_primitive && origins->prim[shadows.path[b + g + k]] == first;
                        const std::span<const Ray> group(batch + g, gm);
                        const std::span<bool> out(blocked + g, gm);
                        if (one_primitive)
                            tracer.occluded_packet(group, out);
                        else
                            tracer.occluded_each(group, out);
                    }
                }
                for (size_t k = 0; k < m; ++k) transmittance[b + k] = blocked[k] ? 0.0f : 1.0f;
            }
        } else {
            for (size_t i = begin; i < end; ++i)
                transmittance[i] = tracer.occluded(shadow_ray_at(shadows, i)) ? 0.0f : 1.0f;
        }
        return end - begin;
    }
    uint64_t rays = 0;
    for (size_t i = begin; i < end; ++i)
        transmittance[i] = wavetrace::transmittance(in.scene, tracer, shadow_ray_at(shadows, i),
                                                    paths.media[shadows.path[i]].unpack(), &rays);
    return rays;
}

}  // namespace wavetrace
