#include "kernels/wave.h"

namespace wavetrace {

void WaveQueues::resize(size_t n) {
    paths.resize(n);
    rays.resize(n);
    next_rays.resize(n);
    hits.resize(n);
    scatter.resize(n);
    shadow_candidates.resize(n);
    shadow.resize(n);
    keep.resize(n);
    shadow_keep.resize(n);
    order.resize(n);
    compacted.resize(n);
    bucket_scratch.resize(n);
}

size_t WaveQueues::bytes_per_path() {
    return PathState::kBytesPerEntry + 2 * RayQueue::kBytesPerEntry + HitQueue::kBytesPerEntry +
           ScatterQueue::kBytesPerEntry + 2 * ShadowQueue::kBytesPerEntry + 2 * sizeof(uint8_t) +
           3 * sizeof(uint32_t);
}

}  // namespace wavetrace
