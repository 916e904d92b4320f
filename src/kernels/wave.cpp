#include "kernels/wave.h"

namespace wavetrace {

void WaveQueues::resize(size_t n) {
    paths.resize(n);
    rays.resize(n);
    hits.resize(n);
    shadows.resize(n);  // at most one shadow ray per path per bounce
    transmittance.resize(n);
    keep.resize(n);
    key.resize(n);
}

}  // namespace wavetrace
