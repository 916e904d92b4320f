#include "kernels/kernels.h"
#include "util/check.h"

namespace wavetrace {

void accumulate_film(const PathQueue& paths,
                     std::span<const uint8_t> keep,
                     size_t begin,
                     size_t end,
                     WaveFilm& film) {
    WT_DCHECK_LE(end, keep.size());
    for (size_t i = begin; i < end; ++i)
        if (!keep[i]) film.radiance[paths.slot[i]] = paths.radiance[i];
}

// A pass gives each pixel its samples in order, and passes run in order, so each pixel receives
// its samples in the same order as in the megakernel, whatever the wave size, thread count or
// schedule. A wave holds distinct pixels, so threads never add to the same pixel.
void add_to_film(const WaveInputs& in,
                 uint32_t first_index,
                 WaveSamples samples,
                 size_t begin,
                 size_t end,
                 const WaveFilm& wave_film,
                 Film& film) {
    if (begin >= end) return;
    const uint32_t width = static_cast<uint32_t>(in.width);
    PassOrderWalk walk(first_index + static_cast<uint32_t>(begin), width,
                       static_cast<uint32_t>(in.height));
    for (size_t p = begin; p < end; ++p, walk.next()) {
        const int pixel = static_cast<int>(walk.y() * width + walk.x());
        for (size_t j = 0; j < samples.per_pixel; ++j)
            film.add(pixel, wave_film.radiance[p * samples.per_pixel + j]);
    }
}

}  // namespace wavetrace
