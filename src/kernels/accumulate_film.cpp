#include "kernels/kernels.h"
#include "util/check.h"

namespace wavetrace {

// A pass gives each pixel one sample, and passes run in order, so each pixel receives its
// samples in the same order as in the megakernel, whatever the wave size, thread count or
// schedule. A wave holds distinct pixels, so threads never add to the same pixel.
void accumulate_film(
    const PathQueue& paths, std::span<const uint8_t> keep, size_t begin, size_t end, Film& film) {
    WT_DCHECK_LE(end, keep.size());
    for (size_t i = begin; i < end; ++i)
        if (!keep[i]) film.add(static_cast<int>(paths.pixel[i]), paths.radiance[i]);
}

}  // namespace wavetrace
