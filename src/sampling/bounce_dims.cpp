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
// then with `flight` pair kPairs, the next bounce's first pair, whose first dimension is the
// next segment's medium distance; padded with pair 0 to any vector length.
struct DrawnPairs {
    uint64_t pair[kPairs + 1 + HWY_MAX_BYTES / 4] = {};
    size_t count = 0;
};
constexpr DrawnPairs drawn_pairs(bool one_sample, bool flight) {
    DrawnPairs l;
    for (uint32_t p = 0; p < kPairs; ++p)
        if (one_sample || !one_sample_pair(p)) l.pair[l.count++] = p;
    if (flight) l.pair[l.count++] = kPairs;
    return l;
}
static_assert(kDimMediumDistance == 0);
constexpr DrawnPairs kDrawnPairs[2][2] = {{drawn_pairs(false, false), drawn_pairs(false, true)},
                                          {drawn_pairs(true, false), drawn_pairs(true, true)}};

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
                    float* u,
                    float* next_flight) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> d32;
    const hn::Rebind<float, D64> df;
    const size_t N = hn::Lanes(d64);
    const DrawnPairs& drawn = kDrawnPairs[one_sample ? 1 : 0][next_flight ? 1 : 0];
    // One path in every lane; lane j holds the (k + j)-th drawn pair p, dimensions first + 2p
    // and the next (lanes past the last pair compute numbers nobody reads).
    const auto state = PathState<L>(sampler, hn::Set(d32, pixel), hn::Set(d32, sample));
    HWY_ALIGN float a[kPairs + 1 + HWY_MAX_BYTES / 4], b[kPairs + 1 + HWY_MAX_BYTES / 4];
#if HWY_TARGET != HWY_SCALAR
    if (sampler.kind != SamplerKind::Independent) {
        // The pairs' hashes in 64-bit lanes, the rest of their formulas on the hashes' words in
        // 32-bit lanes, twice as many to a vector (SobolWords, as DrawSobolVertexSamples).
        using Words = SobolWords<D64>;
        const hn::Rebind<float, Words::D32> dfw;
        const auto reversed_index = sampler.kind == SamplerKind::ZSobol
                                        ? Words::ReversedIndex(state, state)
                                        : Words::W::Set64(ReverseBits32<OneLane>(sample));
        const auto hash = [&](size_t k) {
            return SobolPairHash<L>(
                state, hn::Add(hn::Set(d64, uint64_t(first / 2)), hn::LoadU(d64, drawn.pair + k)));
        };
        for (size_t k = 0; k < drawn.count; k += 2 * N) {
            const auto h0 = hash(k);
            const auto h1 = k + N < drawn.count ? hash(k + N) : h0;
            Words::F va, vb;
            Words::PairDims(reversed_index, h0, h1, &va, &vb);
            hn::Store(va, dfw, a + k);
            hn::Store(vb, dfw, b + k);
        }
    } else
#endif
        for (size_t k = 0; k < drawn.count; k += N) {
            const auto dims = hn::Add(hn::Set(d64, uint64_t(first)),
                                      hn::ShiftLeft<1>(hn::LoadU(d64, drawn.pair + k)));
            hn::Vec<decltype(df)> va, vb;
            SampleDimPair<L>(state, dims, &va, &vb);
            hn::Store(va, df, a + k);
            hn::Store(vb, df, b + k);
        }
    std::fill(u, u + kBounceDims, 0.0f);
    const size_t vertex_pairs = drawn.count - (next_flight ? 1 : 0);
    for (size_t k = 0; k < vertex_pairs; ++k) {
        u[2 * drawn.pair[k]] = a[k];
        u[2 * drawn.pair[k] + 1] = b[k];
    }
    if (next_flight) *next_flight = OpticalDepth<OneLane>(a[vertex_pairs]);
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
                      float u[kBounceDims],
                      float* next_flight) {
    HWY_DYNAMIC_DISPATCH(DrawBounceDims)
    (sampler, pixel, sample, bounce_dim(bounce, BounceDim(0)), one_sample, u, next_flight);
}

}  // namespace wavetrace
#endif  // HWY_ONCE
