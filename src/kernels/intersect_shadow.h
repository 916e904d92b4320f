#pragma once

#include <span>

#include "kernels/wave.h"
#include "shading/trace.h"
#include "wavetrace/scene/intersector.h"

namespace wavetrace {

// Transmittance along shadows[i] (0 if blocked), in the media of its path; returns the rays
// traced.
template <Intersector Tracer>
uint64_t intersect_shadow(const Tracer& tracer,
                          const WaveInputs& in,
                          const ShadowQueue& shadows,
                          const PathQueue& paths,
                          size_t begin,
                          size_t end,
                          std::span<float> transmittance) {
    uint64_t rays = 0;
    for (size_t i = begin; i < end; ++i)
        transmittance[i] = wavetrace::transmittance(
            in.scene, tracer, shadow_ray_at(shadows, i), paths.media[shadows.path[i]].unpack(),
            &rays);
    return rays;
}

}  // namespace wavetrace
