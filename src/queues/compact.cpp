#include "queues/compact.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <vector>

namespace wavetrace {

size_t stable_compact(std::span<const uint8_t> keep, std::span<uint32_t> out) {
    const size_t n = keep.size();
    const size_t chunks = (n + kCompactChunk - 1) / kCompactChunk;
    std::vector<uint32_t> offset(chunks + 1, 0);
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, chunks), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t c = r.begin(); c < r.end(); ++c) {
                uint32_t count = 0;
                for (size_t i = c * kCompactChunk; i < std::min(n, (c + 1) * kCompactChunk); ++i)
                    count += keep[i] != 0;
                offset[c + 1] = count;
            }
        });
    for (size_t c = 0; c < chunks; ++c) offset[c + 1] += offset[c];  // few chunks: serial scan
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, chunks), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t c = r.begin(); c < r.end(); ++c) {
                uint32_t k = offset[c];
                for (size_t i = c * kCompactChunk; i < std::min(n, (c + 1) * kCompactChunk); ++i)
                    if (keep[i]) out[k++] = static_cast<uint32_t>(i);
            }
        });
    return offset[chunks];
}

}  // namespace wavetrace
