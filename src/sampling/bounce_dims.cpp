#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sampling/bounce_dims.cpp"
#include "sampling/bounce_dims.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include "math/lanes-inl.h"
#include "sampling/sampler-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

void DrawBounceDims(
    const Sampler& sampler, uint32_t pixel, uint32_t sample, uint32_t first, float* u) {
    using D64 = hn::ScalableTag<uint64_t>;
    using L = HashLanes<D64>;
    const D64 d64;
    const hn::Rebind<uint32_t, D64> d32;
    const hn::Rebind<float, D64> df;
    const size_t N = hn::Lanes(d64);
    constexpr size_t kPairs = kBounceDims / 2;
    // One path in every lane; lane j holds pair k + j, dimensions first + 2 (k + j) and the next
    // (lanes past the last pair compute numbers nobody reads).
    const auto state = PathState<L>(sampler, hn::Set(d32, pixel), sample);
    HWY_ALIGN float a[kPairs + HWY_MAX_BYTES / 8], b[kPairs + HWY_MAX_BYTES / 8];
    for (size_t k = 0; k < kPairs; k += N) {
        const auto dims =
            hn::Add(hn::Set(d64, uint64_t(first)), hn::ShiftLeft<1>(hn::Iota(d64, uint64_t(k))));
        hn::Vec<decltype(df)> va, vb;
        SampleDimPair<L>(state, dims, &va, &vb);
        hn::Store(va, df, a + k);
        hn::Store(vb, df, b + k);
    }
    for (size_t k = 0; k < kPairs; ++k) {
        u[2 * k] = a[k];
        u[2 * k + 1] = b[k];
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(DrawBounceDims);

void draw_bounce_dims(
    const Sampler& sampler, uint32_t pixel, uint32_t sample, int bounce, float u[kBounceDims]) {
    HWY_DYNAMIC_DISPATCH(DrawBounceDims)(sampler, pixel, sample, bounce_dim(bounce, BounceDim(0)), u);
}

}  // namespace wavetrace
#endif  // HWY_ONCE
