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
    if constexpr (PacketIntersector<Tracer>) {
        if (origins && in.scene.media.empty()) {
            constexpr size_t kPacket = 8;
            Ray batch[kPacket];
            bool blocked[kPacket];
            for (size_t b = begin; b < end; b += kPacket) {
                const size_t m = std::min(kPacket, end - b);
                const PrimRef first = origins->prim[shadows.path[b]];
                bool one_primitive = true;
                for (size_t k = 1; k < m; ++k)
                    one_primitive = one_primitive && origins->prim[shadows.path[b + k]] == first;
                if (!one_primitive) {
                    for (size_t k = b; k < b + m; ++k)
                        transmittance[k] = tracer.occluded(shadow_ray_at(shadows, k)) ? 0.0f : 1.0f;
                    continue;
                }
                for (size_t k = 0; k < m; ++k) batch[k] = shadow_ray_at(shadows, b + k);
                tracer.occluded_packet(std::span<const Ray>(batch, m), std::span<bool>(blocked, m));
                for (size_t k = 0; k < m; ++k) transmittance[b + k] = blocked[k] ? 0.0f : 1.0f;
            }
            return end - begin;
        }
    }
    if (in.scene.media.empty()) {  // a blocker or not: no medium stack to read
        for (size_t i = begin; i < end; ++i)
            transmittance[i] = tracer.occluded(shadow_ray_at(shadows, i)) ? 0.0f : 1.0f;
        return end - begin;
    }
    uint64_t rays = 0;
    for (size_t i = begin; i < end; ++i)
        transmittance[i] = wavetrace::transmittance(in.scene, tracer, shadow_ray_at(shadows, i),
                                                    paths.media[shadows.path[i]].unpack(), &rays);
    return rays;
}

}  // namespace wavetrace
