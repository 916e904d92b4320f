#include "kernels/kernels.h"

namespace wavetrace {

// A wave holds at most one sample per pixel, and waves run in sample order, so each pixel
// receives its samples in the same order as in the megakernel, whatever the wave size.
void accumulate_film(const WaveQueues& q, Film& film, size_t slots) {
    for (size_t slot = 0; slot < slots; ++slot)
        film.add(static_cast<int>(q.paths.pixel[slot]), q.paths.radiance[slot]);
}

}  // namespace wavetrace
