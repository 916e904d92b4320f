#include <algorithm>

#include "blocks/lane_kernels.h"
#include "kernels/kernels.h"
#include "shading/path_vertex.h"
#include "util/check.h"

namespace wavetrace {

// The strategy's weight of each contribution, from the two densities of its sample: emission a
// BSDF-sampled segment found (emission_weight) and each shadow ray's light sample
// (direct_weight). A path has at most one of each per bounce, so entries never share a path;
// its emission is added first, as the megakernel adds it.
void mis_combine(const Estimator& estimator,
                 MisHeuristics heuristics,
                 const EmissionQueue& emissions,
                 EntryRange found,
                 const ShadowQueue& shadows,
                 std::span<const Color> transmittance,
                 EntryRange shadowed,
                 PathQueue& paths) {
    WT_DCHECK_LE(found.end, emissions.capacity);
    WT_DCHECK_LE(shadowed.end, shadows.capacity);
    for (size_t i = found.begin; i < found.end; ++i) {
        WT_DCHECK_LT(emissions.path[i], paths.capacity);
        const float w = emission_weight(
            estimator.strategy, heuristics.of(emissions.flags[i] & kAtInfinity),
            emissions.flags[i] & kCountsFully, emissions.pdf_bsdf[i], emissions.pdf_light[i]);
        paths.radiance[emissions.path[i]] += emissions.radiance[i] * w;
    }
    // The shadow rays' weights a chunk at a time, in SIMD lanes.
    float weight[kShadeChunk];
    for (size_t c = shadowed.begin; c < shadowed.end; c += kShadeChunk) {
        const size_t m = std::min(kShadeChunk, shadowed.end - c);
        direct_weights(estimator.strategy, heuristics.finite, heuristics.at_infinity,
                       &shadows.pdf_light[c], &shadows.pdf_bsdf[c], &shadows.tmax[c], m, weight);
        for (size_t k = 0; k < m; ++k) {
            const size_t i = c + k;
            WT_DCHECK_LT(shadows.path[i], paths.capacity);
            if (weight[k] > 0.0f)
                paths.radiance[shadows.path[i]] +=
                    WAVETRACE_XYZ_AT(shadows, contribution, i) * (weight[k] * transmittance[i]);
        }
    }
}

}  // namespace wavetrace
