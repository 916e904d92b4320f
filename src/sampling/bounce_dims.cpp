#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sampling/bounce_dims.cpp"
#include "sampling/bounce_dims.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>

#include "math/lanes-inl.h"
#include "sampling/sampler-inl.h"

#ifndef WAVETRACE_SAMPLING_BOUNCE_DIMS_PAIRS_
#define WAVETRACE_SAMPLING_BOUNCE_DIMS_PAIRS_
namespace wavetrace {

constexpr size_t kPairs = kBounceDims / 2;
// The pairs a vertex draws, with the one-sample strategies' pairs or without (one_sample_pair),
// padded with pair 0 to any vector length.
struct DrawnPairs {
    uint64_t pair[kPairs + HWY_MAX_BYTES / 8] = {};
    size_t count = 0;
};
constexpr DrawnPairs drawn_pairs(bool one_sample) {
    DrawnPairs l;
    for (uint32_t p = 0; p < kPairs; ++p)
        if (one_sample || !one_sample_pair(p)) l.pair[l.count++] = p;
    return l;
}
constexpr DrawnPairs kDrawnPairs[2] = {drawn_pairs(false), drawn_pairs(true)};

}  // namespace wavetrace
#endif  // WAVETRACE_SAMPLING_BOUNCE_DIMS_PAIRS_

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

void DrawBounceDims(const Sampler& sampler,
                    uint32_t pixel,
                    uint32_t sample,
                    uint32_t first,
                    bool one_sample,
                    float* u) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> d32;
    const hn::Rebind<float, D64> df;
    const size_t N = hn::Lanes(d64);
    const DrawnPairs& drawn = kDrawnPairs[one_sample ? 1 : 0];
    // One path in every lane; lane j holds the (k + j)-th drawn pair p, dimensions first + 2p
    // and the next (lanes past the last pair compute numbers nobody reads).
    const auto state = PathState<L>(sampler, hn::Set(d32, pixel), sample);
    HWY_ALIGN float a[kPairs + HWY_MAX_BYTES / 8], b[kPairs + HWY_MAX_BYTES / 8];
    for (size_t k = 0; k < drawn.count; k += N) {
        const auto dims = hn::Add(hn::Set(d64, uint64_t(first)),
                                  hn::ShiftLeft<1>(hn::LoadU(d64, drawn.pair + k)));
        hn::Vec<decltype(df)> va, vb;
        SampleDimPair<L>(state, dims, &va, &vb);
        hn::Store(va, df, a + k);
        hn::Store(vb, df, b + k);
    }
    std::fill(u, u + kBounceDims, 0.0f);
    for (size_t k = 0; k < drawn.count; ++k) {
        u[2 * drawn.pair[k]] = a[k];
        u[2 * drawn.pair[k] + 1] = b[k];
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(DrawBounceDims);

void draw_bounce_dims(const Sampler& sampler,
                      uint32_t pixel,
                      uint32_t sample,
                      int bounce,
                      bool one_sample,
                      float u[kBounceDims]) {
    HWY_DYNAMIC_DISPATCH(DrawBounceDims)
    (sampler, pixel, sample, bounce_dim(bounce, BounceDim(0)), one_sample, u);
}

}  // namespace wavetrace
#endif  // HWY_ONCE
