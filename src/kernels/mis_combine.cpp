#include "kernels/kernels.h"

namespace wavetrace {

// One shadow ray per path per bounce, so entries never share a path.
void mis_combine(const ShadowQueue& shadows,
                 std::span<const float> transmittance,
                 size_t begin,
                 size_t end,
                 PathQueue& paths) {
    for (size_t i = begin; i < end; ++i)
        paths.radiance[shadows.path[i]] += shadows.contribution[i] * transmittance[i];
}

}  // namespace wavetrace
