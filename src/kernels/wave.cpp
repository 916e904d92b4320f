#include "kernels/wave.h"

namespace wavetrace {

void WaveQueues::resize(size_t n) {
    paths.resize(n);
    rays.resize(n);
    hits.resize(n);
    light_samples.resize(n);  // at most one light sample per path per bounce
    shadows.resize(n);        // and so one shadow ray
    emissions.resize(n);      // and one emitter found
    transmittance.resize(n);
    keep.resize(n);
    key.resize(n);
    film.radiance.resize(n);
}

}  // namespace wavetrace
