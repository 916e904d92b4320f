#include "kernels/kernels.h"

namespace wavetrace {

// In place and stable: entry i only ever moves down to k <= i.
size_t compact(std::span<const uint8_t> keep, size_t n, PathQueue& paths, RayQueue& rays) {
    size_t k = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!keep[i]) continue;
        if (k != i) {
            paths.move(k, i);
            rays.move(k, i);
        }
        ++k;
    }
    return k;
}

}  // namespace wavetrace
