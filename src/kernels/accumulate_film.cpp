#include "kernels/kernels.h"
#include "util/check.h"

namespace wavetrace {

// A pass gives each pixel one sample, and passes run in order, so each pixel receives its
// samples in the same order as in the megakernel, whatever the wave size or thread count.
// Waves hold distinct pixels, so threads never add to the same pixel.
void accumulate_film(const PathQueue& paths, std::span<const uint8_t> keep, size_t n, Film& film) {
    WT_DCHECK_LE(n, keep.size());
    for (size_t i = 0; i < n; ++i)
        if (!keep[i]) film.add(static_cast<int>(paths.pixel[i]), paths.radiance[i]);
}

}  // namespace wavetrace
