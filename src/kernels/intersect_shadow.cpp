#include "kernels/kernels.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

uint64_t intersect_shadow(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end) {
    uint64_t rays = 0;
    for (size_t i = begin; i < end; ++i)
        q.shadow.transmittance[i] =
            transmittance(in.scene, in.bvh, q.shadow.ray[i], q.shadow.media[i], &rays);
    return rays;
}

}  // namespace wavetrace
