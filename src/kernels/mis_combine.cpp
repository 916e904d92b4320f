#include "kernels/kernels.h"
#include "util/check.h"

namespace wavetrace {

// One shadow ray per path per bounce, so entries never share a path.
void mis_combine(const ShadowQueue& shadows,
                 std::span<const float> transmittance,
                 size_t begin,
                 size_t end,
                 PathQueue& paths) {
    WT_DCHECK_LE(end, shadows.capacity);
    for (size_t i = begin; i < end; ++i) {
        WT_DCHECK_LT(shadows.path[i], paths.capacity);
        paths.radiance[shadows.path[i]] += shadows.contribution[i] * transmittance[i];
    }
}

}  // namespace wavetrace
