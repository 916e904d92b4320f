// The counter-based sampler (sampling/sampler.h) over lanes: every uniform number is a pure
// function of (seed, pixel, sample index, dimension), written once for OneLane (the megakernel,
// and sample_1d) and for vectors of paths (the wavefront's draw_vertex_samples). Per-target
// header, see math/lanes-inl.h.
#if defined(WAVETRACE_SAMPLING_SAMPLER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SAMPLING_SAMPLER_INL_H_
#undef WAVETRACE_SAMPLING_SAMPLER_INL_H_
#else
#define WAVETRACE_SAMPLING_SAMPLER_INL_H_
#endif

#include "math/lanes-inl.h"
#include "sampling/sampler.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// SplitMix64's finaliser (Steele et al., "Fast Splittable Pseudorandom Number Generators",
// OOPSLA 2014): a bijective 64-bit mix with full avalanche.
template <class L>
HWY_INLINE typename L::U64 Mix64(typename L::U64 z) {
    z = L::Mul64(L::Xor(z, L::template ShiftRight<30>(z)), L::Set64(0xbf58476d1ce4e5b9ULL));
    z = L::Mul64(L::Xor(z, L::template ShiftRight<27>(z)), L::Set64(0x94d049bb133111ebULL));
    return L::Xor(z, L::template ShiftRight<31>(z));
}

// The state all dimensions of path (pixel, sample) are drawn from: the counters folded in one
// at a time through the mixer, so that neighbouring counters give independent-looking values.
template <class L>
HWY_INLINE typename L::U64 PathState(uint64_t seed, typename L::U32 pixel, uint32_t sample) {
    const uint64_t seeded = Mix64<OneLane>(seed ^ 0x9e3779b97f4a7c15ULL);
    return Mix64<L>(L::Xor(L::Set64(seeded),
                           L::Or64(L::template ShiftLeft<32>(L::Widen(pixel)), L::Set64(sample))));
}

// Dimension `dim` of a path: a uniform float in [0, 1) from the top 24 bits of its hash, so
// that every value is exactly representable.
template <class L>
HWY_INLINE typename L::F SampleDim(typename L::U64 state, typename L::U64 dim) {
    const typename L::U64 h = Mix64<L>(L::Add64(state, dim));
    return L::SmallToFloat(L::template ShiftRight<40>(h)) * L::Set(0x1p-24f);
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SAMPLING_SAMPLER_INL_H_
