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

#include <bit>

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

// A 32-bit hash with low bias (Wellons' "lowbias32", from his hash prospector) of x < 2^32.
template <class L>
HWY_INLINE typename L::U64 Hash32(typename L::U64 x) {
    x = L::Xor(x, L::template ShiftRight<16>(x));
    x = L::MulLow32(x, L::Set64(0x7feb352dULL));
    x = L::Xor(x, L::template ShiftRight<15>(x));
    x = L::MulLow32(x, L::Set64(0x846ca68bULL));
    return L::Xor(x, L::template ShiftRight<16>(x));
}

// The state all dimensions of path (pixel, sample) are drawn from, per lane.
template <class L>
struct SampleState {
    // Independent: the path's hash; Sobol: the pixel's; ZSobol: the path's index into the
    // one sequence: its pixel's Morton index above its sample's bits, digits shuffled.
    typename L::U64 key;
    typename L::U64 sample;
    SamplerKind kind;
    // ZSobol: the hash of the seed and the sample's block (else unused).
    typename L::U64 block_key;
};

// ---- ZSobol (Ahmed & Wonka, "Screen-Space Blue-Noise Diffusion of Monte Carlo Sampling Error
// via Hierarchical Ordering of Pixels", SIGGRAPH Asia 2020, as pbrt-v4's ZSobolSampler uses it)

// x's bits at the even positions of a 64-bit word, y's at the odd ones: the position of pixel
// (x, y) along the Morton (Z-order) curve.
HWY_INLINE uint64_t Morton2(uint32_t x, uint32_t y) {
    auto spread = [](uint64_t v) {
        v = (v | (v << 16)) & 0x0000ffff0000ffffULL;
        v = (v | (v << 8)) & 0x00ff00ff00ff00ffULL;
        v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0fULL;
        v = (v | (v << 2)) & 0x3333333333333333ULL;
        return (v | (v << 1)) & 0x5555555555555555ULL;
    };
    return spread(x) | (spread(y) << 1);
}

// The 24 permutations of a base-4 digit in lexicographic order, eight bits each (the image of
// digit d in bits 2d and 2d + 1), eight to a word.
struct DigitPermutations {
    uint64_t word[3] = {};
    constexpr DigitPermutations() {
        int n = 0;
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b)
                for (int c = 0; c < 4; ++c) {
                    const int d = 6 - a - b - c;
                    if (a == b || a == c || b == c) continue;
                    const uint64_t p = uint64_t(a | b << 2 | c << 4 | d << 6);
                    word[n / 8] |= p << (8 * (n % 8));
                    ++n;
                }
    }
};
constexpr DigitPermutations kDigitPermutations;

// ZSobol's order of the sequence: each base-4 digit of `index` (`digits` of them, from the top;
// the lowest a single bit when log2_spp is odd) replaced by its image under one of the 24
// permutations, chosen by hashing the digits above it with `seed` (Ahmed & Wonka's random
// child order). Each 2 x 2 square of pixels, and of squares, so takes the quarters of its
// block of the sequence in a random order; the quarters together are a net, so that
// neighbouring pixels' errors cancel (blue noise).
template <class L>
HWY_INLINE typename L::U64 ShuffleDigits(typename L::U64 index,
                                         typename L::U64 seed,
                                         int digits,
                                         int odd) {
    using U64 = typename L::U64;
    const DigitPermutations& t = kDigitPermutations;
    auto hash = [&](U64 higher) {
        const U64 folded = L::Xor(higher, L::template ShiftRight<32>(higher));
        return Hash32<L>(L::And64(L::Xor(folded, seed), L::Set64(0xffffffffULL)));
    };
    U64 out = L::Set64(0);
    for (int i = digits - 1; i >= odd; --i) {
        const int shift = 2 * i - odd;
        const U64 digit = L::And64(L::ShiftRightSame(index, shift), L::Set64(3));
        // One of 24 from the hash's top 24 bits, then its word and byte.
        const U64 p = L::template ShiftRight<24>(L::MulLow32(
            L::template ShiftRight<8>(hash(L::ShiftRightSame(index, shift + 2))), L::Set64(24)));
        const U64 q = L::template ShiftRight<3>(p);
        const U64 in_q1 = L::Sub64(L::Set64(0), L::And64(q, L::Set64(1)));
        const U64 in_q2 = L::Sub64(L::Set64(0), L::template ShiftRight<1>(q));
        const U64 word =
            L::Xor(L::Set64(t.word[0]), L::Xor(L::And64(L::Set64(t.word[0] ^ t.word[1]), in_q1),
                                               L::And64(L::Set64(t.word[0] ^ t.word[2]), in_q2)));
        const U64 permutation =
            L::ShiftRightBy(word, L::template ShiftLeft<3>(L::And64(p, L::Set64(7))));
        const U64 image =
            L::And64(L::ShiftRightBy(permutation, L::template ShiftLeft<1>(digit)), L::Set64(3));
        out = L::Or64(out, L::ShiftLeftSame(image, shift));
    }
    if (odd)
        out = L::Or64(out, L::Xor(L::And64(index, L::Set64(1)),
                                  L::And64(hash(L::template ShiftRight<1>(index)), L::Set64(1))));
    return out;
}

// The counters folded in one at a time through the mixer, so that neighbouring counters give
// independent-looking values; the Sobol sampler hashes the pixel alone, its points being
// indexed by the sample.
// Each lane its own path: the wavefront carries several samples of a pixel in one wave.
template <class L>
HWY_INLINE SampleState<L> PathState(const Sampler& sampler,
                                    typename L::U32 pixel,
                                    typename L::U32 sample) {
    const typename L::U64 s64 = L::Widen(sample);
    if (sampler.kind == SamplerKind::ZSobol) {
        // The image's Morton indices run over a square of a power-of-two side; each pixel
        // holds 2^log2_spp consecutive indices, and sample s lies in block s >> log2_spp.
        // (A sampler without its layout, width 0, draws as for a one-pixel-wide image.)
        const uint32_t width = static_cast<uint32_t>(std::max(sampler.width, 1));
        const int log2_spp = sampler.log2_spp;
        const int side_bits =
            std::bit_width(static_cast<unsigned>(std::max({sampler.width, sampler.height, 1}) - 1));
        const typename L::U64 in_block = L::And64(s64, L::Set64((uint64_t(1) << log2_spp) - 1));
        const typename L::U64 block = L::ShiftRightSame(s64, log2_spp);
        const typename L::U64 block_key = Mix64<L>(
            L::Add64(L::Set64(Mix64<OneLane>(sampler.seed ^ 0x3c6ef372fe94f82bULL)), block));
        const typename L::U64 index = L::Or64(
            L::ShiftLeftSame(
                L::MapLanes(pixel, [&](uint32_t p) { return Morton2(p % width, p / width); }),
                log2_spp),
            in_block);
        return {ShuffleDigits<L>(index, L::template ShiftRight<32>(block_key),
                                 side_bits + (log2_spp + 1) / 2, log2_spp & 1),
                s64, sampler.kind, block_key};
    }
    if (sampler.kind == SamplerKind::Sobol) {
        const uint64_t seeded = Mix64<OneLane>(sampler.seed ^ 0x2545f4914f6cdd1dULL);
        return {Mix64<L>(L::Xor(L::Set64(seeded), L::Widen(pixel))), s64, sampler.kind,
                L::Set64(0)};
    }
    const uint64_t seeded = Mix64<OneLane>(sampler.seed ^ 0x9e3779b97f4a7c15ULL);
    return {Mix64<L>(
                L::Xor(L::Set64(seeded), L::Or64(L::template ShiftLeft<32>(L::Widen(pixel)), s64))),
            s64, sampler.kind, L::Set64(0)};
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

// The hash that seeds pair `pair` of a path: its low word the nested scramble of the sample's
// index, its high word the pair's scrambling seed. ZSobol's pair seeds depend on the seed and the
// block, not on the pixel: all pixels draw from one scrambled sequence, whose index (its digits
// shuffled, the path's key) the pair shuffles again as the Sobol sampler shuffles the sample
// index: blocks stay blocks, and the pairs are decorrelated.
template <class L>
HWY_INLINE typename L::U64 SobolPairHash(const SampleState<L>& state, typename L::U64 pair) {
    const bool zsobol = state.kind == SamplerKind::ZSobol;
    return Mix64<L>(L::Add64(zsobol ? state.block_key : state.key, pair));
}

// The pair's state from the bit-reversed index and the hash's two words, in any lanes of
// words below 2^32 (W: OneLane, HashLanes or WordLanes).
template <class W>
HWY_INLINE SobolPairState<W> SobolPairFromHash(typename W::U64 reversed_index,
                                               typename W::U64 low,
                                               typename W::U64 high) {
    return {ReverseBits32<W>(LaineKarras<W>(reversed_index, low)), high};
}

template <class L>
HWY_INLINE SobolPairState<L> SobolPair(const SampleState<L>& state, typename L::U64 pair) {
    const typename L::U64 h = SobolPairHash<L>(state, pair);
    const typename L::U64 reversed_index =
        state.kind == SamplerKind::ZSobol
            ? ReverseBits32<L>(L::And64(state.key, L::Set64(0xffffffffULL)))
            : ReverseBits32<L>(state.sample);
    return SobolPairFromHash<L>(reversed_index, L::And64(h, L::Set64(0xffffffffULL)),
                                L::template ShiftRight<32>(h));
}

// The Owen-scrambled fraction of Sobol bits `t` (in index order), as a float.
template <class L>
HWY_INLINE typename L::F ScrambledSobol(typename L::U64 t, typename L::U64 scramble) {
    return ToUnit<L>(ReverseBits32<L>(LaineKarras<L>(t, scramble)));
}

// The second dimension of a pair is scrambled with a seed of its own.
constexpr uint64_t kSecondScramble = 0x9e3779b9ULL;

// Both dimensions of a pair from its state.
template <class W>
HWY_INLINE void SobolPairDims(const SobolPairState<W>& p, typename W::F* a, typename W::F* b) {
    *a = ScrambledSobol<W>(p.index, p.scramble);
    *b = ScrambledSobol<W>(SobolSecond<W>(p.index), W::Xor(p.scramble, W::Set64(kSecondScramble)));
}

#if HWY_TARGET != HWY_SCALAR
// The Sobol samplers' formulas past the hash on the hashes' 32-bit words (WordLanes), twice as
// many to a vector as the 64-bit lanes the hashes take: two vectors of hashes, of keys, become
// one of words. What the engines' lane draws share (the wavefront's rows of paths, the
// megakernel's pairs of one path).
template <class D64>
struct SobolWords {
    using D32 = hn::Repartition<uint32_t, D64>;
    using W = WordLanes<D32>;
    using U64 = hn::Vec<D64>;
    using F = hn::Vec<hn::Rebind<float, D32>>;

    // The low or high words of the lanes of a, then of b.
    static HWY_INLINE typename W::U64 Low(U64 a, U64 b) {
        return hn::ConcatEven(D32(), hn::BitCast(D32(), b), hn::BitCast(D32(), a));
    }
    static HWY_INLINE typename W::U64 High(U64 a, U64 b) {
        return hn::ConcatOdd(D32(), hn::BitCast(D32(), b), hn::BitCast(D32(), a));
    }
    // The bit-reversed sample indices of the paths whose states are s0, then s1 (ZSobol's
    // index is the key's low word; Sobol's the sample's).
    template <class L>
    static HWY_INLINE typename W::U64 ReversedIndex(const SampleState<L>& s0,
                                                    const SampleState<L>& s1) {
        return W::ReverseBits32(s0.kind == SamplerKind::ZSobol ? Low(s0.key, s1.key)
                                                               : Low(s0.sample, s1.sample));
    }
    // Both dimensions of the pairs whose hashes (SobolPairHash) are h0, then h1.
    static HWY_INLINE void PairDims(typename W::U64 reversed_index, U64 h0, U64 h1, F* a, F* b) {
        SobolPairDims<W>(SobolPairFromHash<W>(reversed_index, Low(h0, h1), High(h0, h1)), a, b);
    }
};
#endif

// Dimension `dim` of a path, a uniform float in [0, 1):
// - Independent: a hash of the path's state and the dimension.
// - Sobol: dimensions (2k, 2k + 1) are the two dimensions of Sobol's (0, 2)-sequence at the
//   sample's index shuffled by a nested uniform scramble seeded per pixel and pair (Burley's
//   padding: every power-of-two prefix of a pixel's samples stays a (0, m, 2)-net in each
//   pair, and different pairs are decorrelated), each dimension then Owen-scrambled with its
//   own seed.
template <class L>
HWY_INLINE typename L::F SampleDim(const SampleState<L>& state, typename L::U64 dim) {
    if (state.kind != SamplerKind::Independent) {
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
    if (state.kind != SamplerKind::Independent) {
        SobolPairDims<L>(SobolPair<L>(state, L::template ShiftRight<1>(first)), a, b);
        return;
    }
    *a = SampleDim<L>(state, first);
    *b = SampleDim<L>(state, L::Add64(first, L::Set64(1)));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SAMPLING_SAMPLER_INL_H_
