#include "kernels/kernels.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

// One shadow ray per path per bounce, so entries never share a path: no races.
void mis_combine(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end) {
    const ShadowQueue& s = q.shadow;
    for (size_t i = begin; i < end; ++i) {
        float w =
            direct_weight(in.config.strategy, in.config.heuristic, s.pdf_light[i], s.pdf_bsdf[i]);
        q.paths.radiance[s.path[i]] += s.contribution[i] * (w * s.transmittance[i]);
    }
}

}  // namespace wavetrace
