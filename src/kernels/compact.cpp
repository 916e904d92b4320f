#include <algorithm>
#include <cstdint>

#include "kernels/kernels.h"
#include "util/check.h"

namespace wavetrace {
namespace {

constexpr size_t kBlock = 256;

// Where the kept entries among [begin, end) (at most kBlock) come from, in order; their count.
size_t kept_in_block(std::span<const uint8_t> keep, size_t begin, size_t end, uint32_t* from) {
    size_t m = 0;
    for (size_t i = begin; i < end; ++i) {
        from[m] = static_cast<uint32_t>(i);
        m += keep[i] != 0;
    }
    return m;
}

}  // namespace

// In place and stable: entry i only ever moves down to k <= i. A block of entries at a time:
// first where each kept entry comes from, then each field moved for the whole block (a tight
// loop per array rather than every array per entry).
size_t compact(std::span<const uint8_t> keep, size_t n, PathQueue& paths, RayQueue& rays) {
    size_t k = 0;
    for (size_t b = 0; b < n; b += kBlock) {
        uint32_t from[kBlock];
        const size_t m = kept_in_block(keep, b, std::min(n, b + kBlock), from);
        if (m > 0 && from[m - 1] != k + m - 1) {  // else every kept entry stays where it is
            paths.gather(k, from, m);
            rays.gather(k, from, m);
        }
        k += m;
    }
    return k;
}

size_t compact_into(std::span<const uint8_t> keep,
                    size_t begin,
                    size_t end,
                    const PathQueue& paths,
                    const RayQueue& rays,
                    size_t to,
                    PathQueue& next_paths,
                    RayQueue& next_rays) {
    size_t k = to;
    for (size_t b = begin; b < end; b += kBlock) {
        uint32_t from[kBlock];
        const size_t m = kept_in_block(keep, b, std::min(end, b + kBlock), from);
        WT_DCHECK_LE(k + m, next_paths.capacity);
        next_paths.copy(k, paths, from, m);
        next_rays.copy(k, rays, from, m);
        k += m;
    }
    return k - to;
}

}  // namespace wavetrace
