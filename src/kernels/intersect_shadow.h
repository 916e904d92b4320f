#pragma once

#include <algorithm>
#include <span>

#include "kernels/intersect.h"
#include "kernels/wave.h"
#include "scene/intersector.h"
#include "shading/trace.h"

namespace wavetrace {

// Transmittance along shadows[i] (0 if blocked), in the media of its path; returns the rays
// traced. `coherent`: the rays leave the camera rays' hits, in pixel tiles, and are traced as
// packets where the intersector has them and no medium needs tracking.
template <Intersector Tracer>
uint64_t intersect_shadow(const Tracer& tracer,
                          const WaveInputs& in,
                          const ShadowQueue& shadows,
                          const PathQueue& paths,
                          size_t begin,
                          size_t end,
                          std::span<float> transmittance,
                          bool coherent = false) {
    if constexpr (PacketIntersector<Tracer>) {
        if (coherent && in.scene.media.empty()) {
            constexpr size_t kBatch = 64;
            Ray batch[kBatch];
            bool blocked[kBatch];
            for (size_t b = begin; b < end; b += kBatch) {
                const size_t m = std::min(kBatch, end - b);
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
