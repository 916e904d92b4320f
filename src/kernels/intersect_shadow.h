#pragma once

#include "kernels/wave.h"
#include "shading/trace.h"
#include "wavetrace/scene/intersector.h"

namespace wavetrace {

// Transmittance along shadow[i] (0 if blocked); returns the rays traced.
template <Intersector Tracer>
uint64_t intersect_shadow(
    const Tracer& tracer, const WaveInputs& in, WaveQueues& q, size_t begin, size_t end) {
    uint64_t rays = 0;
    for (size_t i = begin; i < end; ++i)
        q.shadow.transmittance[i] =
            transmittance(in.scene, tracer, q.shadow.ray[i], q.shadow.media[i], &rays);
    return rays;
}

}  // namespace wavetrace
