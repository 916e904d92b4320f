// Stable stream compaction without an atomic per item: count the kept entries of each chunk,
// take an exclusive prefix sum over the chunks, then let each chunk write its kept indices at
// its offset (the scheme of Cycles' parallel_active_index.h, on oneTBB).
#pragma once

#include <cstdint>
#include <span>

namespace wavetrace {

inline constexpr size_t kCompactChunk = 2048;

// Writes, in increasing order, the indices i with keep[i] != 0 to out[0, count) and returns
// count. `out` must hold keep.size() entries. The result does not depend on thread count.
size_t stable_compact(std::span<const uint8_t> keep, std::span<uint32_t> out);

}  // namespace wavetrace
