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

// The state all dimensions of path (pixel, sample) are drawn from.
template <class L>
struct SampleState {
    typename L::U64 key;  // independent: the path's hash; Sobol: the pixel's
    uint32_t sample;
    SamplerKind kind;
};

// The counters folded in one at a time through the mixer, so that neighbouring counters give
// independent-looking values; the Sobol sampler hashes the pixel alone, its points being
// indexed by the sample.
template <class L>
HWY_INLINE SampleState<L> PathState(const Sampler& sampler,
                                    typename L::U32 pixel,
                                    uint32_t sample) {
    if (sampler.kind == SamplerKind::Sobol) {
        const uint64_t seeded = Mix64<OneLane>(sampler.seed ^ 0x2545f4914f6cdd1dULL);
        return {Mix64<L>(L::Xor(L::Set64(seeded), L::Widen(pixel))), sample, sampler.kind};
    }
    const uint64_t seeded = Mix64<OneLane>(sampler.seed ^ 0x9e3779b97f4a7c15ULL);
    return {Mix64<L>(L::Xor(L::Set64(seeded),
                            L::Or64(L::template ShiftLeft<32>(L::Widen(pixel)), L::Set64(sample)))),
            sample, sampler.kind};
}

// ---- Owen-scrambled Sobol points (Burley, "Practical Hash-based Owen Scrambling", JCGT 2020)
// 32-bit words in the low half of 64-bit lanes.

// Bits 0..31 in reverse order (a word's index bits as a binary fraction and back).
template <class L>
HWY_INLINE typename L::U64 ReverseBits32(typename L::U64 x) {
    return L::ReverseBits32(x);
}

// Burley's variant of the Laine-Karras hash: a permutation of 32-bit words in which bit k is
// flipped as a function of the seed and bits 0..k-1 only (additions and products by even
// constants carry upwards). On bit-reversed values that is Owen's nested uniform scrambling.
template <class L>
HWY_INLINE typename L::U64 LaineKarras(typename L::U64 x, typename L::U64 seed) {
    x = L::And64(L::Add64(x, seed), L::Set64(0xffffffffULL));
    x = L::Xor(x, L::MulLow32(x, L::Set64(0x6c50b47cULL)));
    x = L::Xor(x, L::MulLow32(x, L::Set64(0xb82f1e52ULL)));
    x = L::Xor(x, L::MulLow32(x, L::Set64(0xc7afe638ULL)));
    return L::Xor(x, L::MulLow32(x, L::Set64(0x8d22f6e6ULL)));
}

// Sobol's second dimension before the bit reversal: its generator matrix is Pascal's triangle
// modulo 2 (the direction numbers of the polynomial x + 1), so by Lucas' theorem the bit at
// position p is the XOR of the index bits at positions j that contain p's bits: a sum over
// supersets of the five position bits, one shift-and-XOR per bit. (The first dimension is
// the index itself: the van der Corput sequence.)
template <class L>
HWY_INLINE typename L::U64 SobolSecond(typename L::U64 t) {
    t = L::Xor(t, L::And64(L::template ShiftRight<1>(t), L::Set64(0x55555555)));
    t = L::Xor(t, L::And64(L::template ShiftRight<2>(t), L::Set64(0x33333333)));
    t = L::Xor(t, L::And64(L::template ShiftRight<4>(t), L::Set64(0x0f0f0f0f)));
    t = L::Xor(t, L::And64(L::template ShiftRight<8>(t), L::Set64(0x00ff00ff)));
    return L::Xor(t, L::And64(L::template ShiftRight<16>(t), L::Set64(0x0000ffff)));
}

// A 32-bit value as a uniform float in [0, 1): its top 24 bits, so that every value is
// exactly representable.
template <class L>
HWY_INLINE typename L::F ToUnit(typename L::U64 value) {
    return L::SmallToFloat(L::template ShiftRight<8>(value)) * L::Set(0x1p-24f);
}

// What dimensions (2k, 2k + 1) of a Sobol path share: the sample's index shuffled by a nested
// uniform scramble seeded per pixel and pair, and the pair's scrambling seed.
template <class L>
struct SobolPairState {
    typename L::U64 index;
    typename L::U64 scramble;
};

template <class L>
HWY_INLINE SobolPairState<L> SobolPair(const SampleState<L>& state, typename L::U64 pair) {
    const typename L::U64 h = Mix64<L>(L::Add64(state.key, pair));
    const typename L::U64 shuffle = L::And64(h, L::Set64(0xffffffffULL));
    const uint64_t reversed_sample = ReverseBits32<OneLane>(state.sample);
    return {ReverseBits32<L>(LaineKarras<L>(L::Set64(reversed_sample), shuffle)),
            L::template ShiftRight<32>(h)};
}

// The Owen-scrambled fraction of Sobol bits `t` (in index order), as a float.
template <class L>
HWY_INLINE typename L::F ScrambledSobol(typename L::U64 t, typename L::U64 scramble) {
    return ToUnit<L>(ReverseBits32<L>(LaineKarras<L>(t, scramble)));
}

// The second dimension of a pair is scrambled with a seed of its own.
constexpr uint64_t kSecondScramble = 0x9e3779b9ULL;

// Dimension `dim` of a path, a uniform float in [0, 1):
// - Independent: a hash of the path's state and the dimension.
// - Sobol: dimensions (2k, 2k + 1) are the two dimensions of Sobol's (0, 2)-sequence at the
//   sample's index shuffled by a nested uniform scramble seeded per pixel and pair (Burley's
//   padding: every power-of-two prefix of a pixel's samples stays a (0, m, 2)-net in each
//   pair, and different pairs are decorrelated), each dimension then Owen-scrambled with its
//   own seed.
template <class L>
HWY_INLINE typename L::F SampleDim(const SampleState<L>& state, typename L::U64 dim) {
    if (state.kind == SamplerKind::Sobol) {
        const SobolPairState<L> p = SobolPair<L>(state, L::template ShiftRight<1>(dim));
        const typename L::U64 odd = L::And64(dim, L::Set64(1));
        const typename L::U64 all_if_odd = L::Sub64(L::Set64(0), odd);
        const typename L::U64 t = L::Xor(
            p.index, L::And64(L::Xor(SobolSecond<L>(p.index), p.index), all_if_odd));
        return ScrambledSobol<L>(
            t, L::Xor(p.scramble, L::And64(L::Set64(kSecondScramble), all_if_odd)));
    }
    return ToUnit<L>(L::template ShiftRight<32>(Mix64<L>(L::Add64(state.key, dim))));
}

// Dimensions `first` and `first` + 1 (`first` even) at once, what SampleDim gives for each,
// with what the two share computed once.
template <class L>
HWY_INLINE void SampleDimPair(const SampleState<L>& state,
                              typename L::U64 first,
                              typename L::F* a,
                              typename L::F* b) {
    if (state.kind == SamplerKind::Sobol) {
        const SobolPairState<L> p = SobolPair<L>(state, L::template ShiftRight<1>(first));
        *a = ScrambledSobol<L>(p.index, p.scramble);
        *b = ScrambledSobol<L>(SobolSecond<L>(p.index),
                               L::Xor(p.scramble, L::Set64(kSecondScramble)));
        return;
    }
    *a = SampleDim<L>(state, first);
    *b = SampleDim<L>(state, L::Add64(first, L::Set64(1)));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SAMPLING_SAMPLER_INL_H_
