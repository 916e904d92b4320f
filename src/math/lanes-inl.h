// Lane types: the transport formulas that both engines run are written once, as templates over
// a lane type L, and instantiated twice:
//   OneLane           one path at a time, plain scalar C++: what the megakernel runs;
//   FloatLanes<D>     a vector of paths (Highway tag D): what the wavefront's kernels run over
//   HashLanes<D64>    the sorted ranges of a wave, in as many lanes as the CPU's vectors hold.
// The formulas use only +, -, *, / and the operations below, which give the same bits in a
// lane as in scalar code (IEEE operations, no fused multiply-adds: -ffp-contract=off), so the
// two engines trace the same paths. This is Mitsuba 3's / Dr.Jit's "one code, scalar or packet"
// (Jakob et al., "Dr.Jit", SIGGRAPH 2022), with Highway's runtime dispatch picking the vector
// target (SSE4, AVX2, AVX-512, NEON).
//
// Per-target header (Highway's -inl.h convention): a translation unit under foreach_target.h
// gets a copy per target; any other gets the static target's, whose OneLane instances are the
// scalar functions (Frame::from_normal, origin_offset, sample_1d, ...).
#if defined(WAVETRACE_MATH_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_MATH_LANES_INL_H_
#undef WAVETRACE_MATH_LANES_INL_H_
#else
#define WAVETRACE_MATH_LANES_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "wavetrace/math/vec3.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// ---- the lane types ------------------------------------------------------------------------

struct OneLane {
    using F = float;
    using M = bool;
    using U32 = uint32_t;
    using U64 = uint64_t;

    static F Set(float x) { return x; }
    static F Sqrt(F x) { return std::sqrt(x); }
    static F Abs(F x) { return std::fabs(x); }
    static F Min(F a, F b) { return b < a ? b : a; }
    static F Max(F a, F b) { return a < b ? b : a; }
    static F Neg(F x) { return -x; }
    static F CopySign(F magnitude, F sign) { return std::copysign(magnitude, sign); }
    static F Round(F x) { return std::nearbyint(x); }  // to nearest, ties to even
    static F Select(M m, F yes, F no) { return m ? yes : no; }
    static M IsInf(F x) { return std::isinf(x); }
    static M IsFinite(F x) { return std::isfinite(x); }
    static M And(M a, M b) { return a && b; }
    static M Or(M a, M b) { return a || b; }
    static M AndNot(M not_a, M b) { return !not_a && b; }
    static M Not(M m) { return !m; }
    static bool Any(M m) { return m; }
    static M All() { return true; }
    // x = m 2^e for a positive normal x, m in [1, 2): returns e, sets *m (exact).
    static F SplitExponent(F x, F* m) {
        uint32_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        const uint32_t m_bits = (bits & 0x007fffffu) | 0x3f800000u;
        std::memcpy(m, &m_bits, sizeof m_bits);
        return static_cast<float>(static_cast<int32_t>(bits >> 23) - 127);
    }

    // 32-bit integer lanes, for table indices and exponents: Trunc of a float in (-2^31, 2^31)
    // toward zero, Gather of base[i] (i >= 0).
    using I = int32_t;
    // 2^e for an integer e in [-126, 127], exactly.
    static F Pow2(I e) {
        const uint32_t bits = static_cast<uint32_t>(e + 127) << 23;
        float f;
        std::memcpy(&f, &bits, sizeof f);
        return f;
    }
    static I SetI(int32_t x) { return x; }
    static I AddI(I a, I b) { return a + b; }
    static I SubI(I a, I b) { return a - b; }
    static I MulI(I a, I b) { return a * b; }
    static I MinI(I a, I b) { return b < a ? b : a; }
    static I SelectI(M m, I yes, I no) { return m ? yes : no; }
    static I Trunc(F x) { return static_cast<int32_t>(x); }
    static F ToFloat(I x) { return static_cast<float>(x); }
    static F Floor(F x) { return std::floor(x); }
    static F Gather(const float* base, I i) { return base[i]; }
    static I GatherI(const int32_t* base, I i) { return base[i]; }
    static I HalfI(I a) { return a >> 1; }  // a >= 0
    static bool AnyAbove(I a, int32_t b) { return a > b; }

    static U64 Set64(uint64_t x) { return x; }
    static U64 Widen(U32 x) { return x; }
    template <int kBits>
    static U64 ShiftRight(U64 x) {
        return x >> kBits;
    }
    template <int kBits>
    static U64 ShiftLeft(U64 x) {
        return x << kBits;
    }
    static U64 Xor(U64 a, U64 b) { return a ^ b; }
    static U64 Or64(U64 a, U64 b) { return a | b; }
    static U64 And64(U64 a, U64 b) { return a & b; }
    static U64 Add64(U64 a, U64 b) { return a + b; }
    static U64 Sub64(U64 a, U64 b) { return a - b; }
    static U64 Mul64(U64 a, U64 b) { return a * b; }  // modulo 2^64
    static U64 ShiftRightBy(U64 x, U64 bits) { return x >> bits; }  // bits < 64, per lane
    static U64 ShiftRightSame(U64 x, int bits) { return x >> bits; }
    static U64 ShiftLeftSame(U64 x, int bits) { return x << bits; }
    // f(lane) of each 32-bit lane, for what has no lane formula (a division).
    template <class Fn>
    static U64 MapLanes(U32 x, Fn f) {
        return f(x);
    }
    // The product of the low 32 bits of each, modulo 2^32.
    static U64 MulLow32(U64 a, U64 b) { return uint32_t(a) * uint32_t(b); }
    // Bits 0..31 in reverse order, of a value below 2^32: five swaps of halves.
    static U64 ReverseBits32(U64 x) {
        x = ((x >> 1) & 0x55555555) | ((x & 0x55555555) << 1);
        x = ((x >> 2) & 0x33333333) | ((x & 0x33333333) << 2);
        x = ((x >> 4) & 0x0f0f0f0f) | ((x & 0x0f0f0f0f) << 4);
        x = ((x >> 8) & 0x00ff00ff) | ((x & 0x00ff00ff) << 8);
        return ((x >> 16) & 0x0000ffff) | ((x & 0x0000ffff) << 16);
    }
    static F SmallToFloat(U64 x) { return static_cast<float>(x); }  // x < 2^24: exact
};

template <class D>
struct FloatLanes {
    using F = hn::Vec<D>;
    using M = hn::Mask<D>;

    static HWY_INLINE F Set(float x) { return hn::Set(D(), x); }
    static HWY_INLINE F Sqrt(F x) { return hn::Sqrt(x); }
    static HWY_INLINE F Abs(F x) { return hn::Abs(x); }
    static HWY_INLINE F Min(F a, F b) { return hn::Min(a, b); }
    static HWY_INLINE F Max(F a, F b) { return hn::Max(a, b); }
    static HWY_INLINE F Neg(F x) { return hn::Neg(x); }
    static HWY_INLINE F CopySign(F magnitude, F sign) { return hn::CopySign(magnitude, sign); }
    static HWY_INLINE F Round(F x) { return hn::Round(x); }
    static HWY_INLINE F Select(M m, F yes, F no) { return hn::IfThenElse(m, yes, no); }
    static HWY_INLINE M IsInf(F x) { return hn::IsInf(x); }
    static HWY_INLINE M IsFinite(F x) { return hn::IsFinite(x); }
    static HWY_INLINE M And(M a, M b) { return hn::And(a, b); }
    static HWY_INLINE M Or(M a, M b) { return hn::Or(a, b); }
    static HWY_INLINE M AndNot(M not_a, M b) { return hn::AndNot(not_a, b); }
    static HWY_INLINE M Not(M m) { return hn::Not(m); }
    static HWY_INLINE bool Any(M m) { return !hn::AllFalse(D(), m); }
    static HWY_INLINE M All() { return hn::FirstN(D(), hn::Lanes(D())); }  // every lane set
    using I = hn::Vec<hn::RebindToSigned<D>>;
    static HWY_INLINE I SetI(int32_t x) { return hn::Set(hn::RebindToSigned<D>(), x); }
    static HWY_INLINE I AddI(I a, I b) { return hn::Add(a, b); }
    static HWY_INLINE I SubI(I a, I b) { return hn::Sub(a, b); }
    static HWY_INLINE I MulI(I a, I b) { return hn::Mul(a, b); }
    static HWY_INLINE I MinI(I a, I b) { return hn::Min(a, b); }
    static HWY_INLINE I SelectI(M m, I yes, I no) {
        return hn::IfThenElse(hn::RebindMask(hn::RebindToSigned<D>(), m), yes, no);
    }
    static HWY_INLINE I Trunc(F x) { return hn::ConvertTo(hn::RebindToSigned<D>(), x); }
    static HWY_INLINE F ToFloat(I x) { return hn::ConvertTo(D(), x); }
    static HWY_INLINE F Pow2(I e) {
        const hn::RebindToSigned<D> di;
        return hn::BitCast(D(), hn::ShiftLeft<23>(hn::Add(e, hn::Set(di, 127))));
    }
    static HWY_INLINE F Floor(F x) { return hn::Floor(x); }
    static HWY_INLINE F Gather(const float* base, I i) { return hn::GatherIndex(D(), base, i); }
    static HWY_INLINE I GatherI(const int32_t* base, I i) {
        return hn::GatherIndex(hn::RebindToSigned<D>(), base, i);
    }
    static HWY_INLINE I HalfI(I a) { return hn::ShiftRight<1>(a); }  // a >= 0
    // A hint that base[i] will be read soon, each lane's own (the wavefront's staged kernels
    // only: one lane has nothing to overlap).
    template <class T>
    static HWY_INLINE void Prefetch(const T* base, I i) {
        const hn::RebindToSigned<D> di;
        HWY_ALIGN int32_t at[hn::MaxLanes(di)];
        hn::Store(i, di, at);
        for (size_t l = 0; l < hn::Lanes(di); ++l) __builtin_prefetch(base + at[l]);
    }
    static HWY_INLINE bool AnyAbove(I a, int32_t b) {
        const hn::RebindToSigned<D> di;
        return !hn::AllFalse(di, hn::Gt(a, hn::Set(di, b)));
    }
    static HWY_INLINE F SplitExponent(F x, F* m) {
        const hn::RebindToSigned<D> di;
        const auto bits = hn::BitCast(di, x);
        *m = hn::BitCast(D(),
                         hn::Or(hn::And(bits, hn::Set(di, 0x007fffff)), hn::Set(di, 0x3f800000)));
        return hn::ConvertTo(D(), hn::Sub(hn::ShiftRight<23>(bits), hn::Set(di, 127)));
    }
};

#if HWY_TARGET != HWY_SCALAR
// The bits of every 32-bit word of x in reverse order: each nibble reversed by a 16-entry
// byte table, the nibbles of each byte swapped, then the four bytes of each word reversed.
template <class D>
HWY_INLINE hn::Vec<D> ReverseWordBits(D d, hn::Vec<D> x) {
    const hn::Repartition<uint8_t, D> d8;
    alignas(16) static constexpr uint8_t kNibbles[16] = {0, 8, 4, 12, 2, 10, 6, 14,
                                                         1, 9, 5, 13, 3, 11, 7, 15};
    alignas(16) static constexpr uint8_t kBytes[16] = {3,  2,  1, 0, 7,  6,  5,  4,
                                                       11, 10, 9, 8, 15, 14, 13, 12};
    const auto table = hn::LoadDup128(d8, kNibbles);
    const auto low = hn::And(hn::BitCast(d8, x), hn::Set(d8, 0x0f));
    const auto high = hn::And(hn::BitCast(d8, hn::ShiftRight<4>(x)), hn::Set(d8, 0x0f));
    const auto swapped = hn::Or(hn::ShiftLeft<4>(hn::BitCast(d, hn::TableLookupBytes(table, low))),
                                hn::BitCast(d, hn::TableLookupBytes(table, high)));
    return hn::BitCast(d,
                       hn::TableLookupBytes(hn::BitCast(d8, swapped), hn::LoadDup128(d8, kBytes)));
}
#endif

// 64-bit integer lanes with floats of the same lane count (half the vector width).
template <class D64>
struct HashLanes : FloatLanes<hn::Rebind<float, D64>> {
    using D32 = hn::Rebind<uint32_t, D64>;
    using U32 = hn::Vec<D32>;
    using U64 = hn::Vec<D64>;
    using typename FloatLanes<hn::Rebind<float, D64>>::F;

    static HWY_INLINE U64 Set64(uint64_t x) { return hn::Set(D64(), x); }
    static HWY_INLINE U64 Widen(U32 x) { return hn::PromoteTo(D64(), x); }
    template <int kBits>
    static HWY_INLINE U64 ShiftRight(U64 x) {
        return hn::ShiftRight<kBits>(x);
    }
    template <int kBits>
    static HWY_INLINE U64 ShiftLeft(U64 x) {
        return hn::ShiftLeft<kBits>(x);
    }
    static HWY_INLINE U64 Xor(U64 a, U64 b) { return hn::Xor(a, b); }
    static HWY_INLINE U64 Or64(U64 a, U64 b) { return hn::Or(a, b); }
    static HWY_INLINE U64 And64(U64 a, U64 b) { return hn::And(a, b); }
    static HWY_INLINE U64 Add64(U64 a, U64 b) { return hn::Add(a, b); }
    static HWY_INLINE U64 Sub64(U64 a, U64 b) { return hn::Sub(a, b); }
    static HWY_INLINE U64 ShiftRightBy(U64 x, U64 bits) { return hn::Shr(x, bits); }
    static HWY_INLINE U64 ShiftRightSame(U64 x, int bits) { return hn::ShiftRightSame(x, bits); }
    static HWY_INLINE U64 ShiftLeftSame(U64 x, int bits) { return hn::ShiftLeftSame(x, bits); }
    template <class Fn>
    static HWY_INLINE U64 MapLanes(U32 x, Fn f) {
        HWY_ALIGN uint32_t in[HWY_MAX_BYTES / 8];
        HWY_ALIGN uint64_t out[HWY_MAX_BYTES / 8];
        hn::Store(x, D32(), in);
        for (size_t i = 0; i < hn::Lanes(D64()); ++i) out[i] = f(in[i]);
        return hn::Load(D64(), out);
    }
    static HWY_INLINE U64 MulLow32(U64 a, U64 b) {
#if HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128
        const D64 d;
        HWY_ALIGN uint64_t x[2], y[2];
        hn::Store(a, d, x);
        hn::Store(b, d, y);
        for (size_t i = 0; i < hn::Lanes(d); ++i) x[i] = uint32_t(x[i]) * uint32_t(y[i]);
        return hn::Load(d, x);
#else
        const hn::Repartition<uint32_t, D64> d32;
        return hn::And(hn::MulEven(hn::BitCast(d32, a), hn::BitCast(d32, b)),
                       hn::Set(D64(), 0xffffffffULL));
#endif
    }
    static HWY_INLINE U64 Mul64(U64 a, U64 b) {
#if HWY_TARGET <= HWY_AVX3 && HWY_ARCH_X86
        return hn::Mul(a, b);
#elif HWY_TARGET == HWY_SCALAR || HWY_TARGET == HWY_EMU128
        // At most two lanes: one at a time.
        const D64 d;
        HWY_ALIGN uint64_t x[2], y[2];
        hn::Store(a, d, x);
        hn::Store(b, d, y);
        for (size_t i = 0; i < hn::Lanes(d); ++i) x[i] *= y[i];
        return hn::Load(d, x);
#else
        // The low 64 bits of a * b from 32-bit halves: lo*lo + ((hi*lo + lo*hi) << 32).
        const hn::Repartition<uint32_t, D64> d32;
        const U64 a_hi = hn::ShiftRight<32>(a), b_hi = hn::ShiftRight<32>(b);
        const U64 lo = hn::MulEven(hn::BitCast(d32, a), hn::BitCast(d32, b));
        const U64 cross = hn::Add(hn::MulEven(hn::BitCast(d32, a_hi), hn::BitCast(d32, b)),
                                  hn::MulEven(hn::BitCast(d32, a), hn::BitCast(d32, b_hi)));
        return hn::Add(lo, hn::ShiftLeft<32>(cross));
#endif
    }
    // Bits 0..31 in reverse order, of values below 2^32 (ReverseWordBits; the high word, zero,
    // stays zero).
    static HWY_INLINE U64 ReverseBits32(U64 x) {
#if HWY_TARGET == HWY_SCALAR
        return hn::Set(D64(), OneLane::ReverseBits32(hn::GetLane(x)));
#else
        return ReverseWordBits(D64(), x);
#endif
    }
    static HWY_INLINE F SmallToFloat(U64 x) {
        const hn::Rebind<int32_t, D64> di;
        return hn::ConvertTo(hn::Rebind<float, D64>(), hn::BitCast(di, hn::TruncateTo(D32(), x)));
    }
};

#if HWY_TARGET != HWY_SCALAR
// 32-bit words in 32-bit lanes, floats of the same lane count (twice HashLanes' per vector):
// the operations the sampler's formulas apply to words below 2^32 (sampling/sampler-inl.h's
// LaineKarras, SobolSecond, ReverseBits32, ToUnit), under HashLanes' names, so that one
// formula serves 64-bit lanes, one lane and these. (U64 is the word vector here.)
template <class D32>
struct WordLanes : FloatLanes<hn::Rebind<float, D32>> {
    using U64 = hn::Vec<D32>;
    using typename FloatLanes<hn::Rebind<float, D32>>::F;

    static HWY_INLINE U64 Set64(uint64_t x) { return hn::Set(D32(), uint32_t(x)); }
    template <int kBits>
    static HWY_INLINE U64 ShiftRight(U64 x) {
        return hn::ShiftRight<kBits>(x);
    }
    static HWY_INLINE U64 Xor(U64 a, U64 b) { return hn::Xor(a, b); }
    static HWY_INLINE U64 And64(U64 a, U64 b) { return hn::And(a, b); }
    static HWY_INLINE U64 Add64(U64 a, U64 b) { return hn::Add(a, b); }
    static HWY_INLINE U64 MulLow32(U64 a, U64 b) { return hn::Mul(a, b); }
    static HWY_INLINE U64 ReverseBits32(U64 x) { return ReverseWordBits(D32(), x); }
    static HWY_INLINE F SmallToFloat(U64 x) {
        return hn::ConvertTo(hn::Rebind<float, D32>(), hn::BitCast(hn::RebindToSigned<D32>(), x));
    }
};
#endif

// ---- 3-vectors of lanes ----------------------------------------------------------------------

template <class F>
struct V3 {
    F x, y, z;
};

template <class F>
HWY_INLINE V3<F> operator+(V3<F> a, V3<F> b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class F>
HWY_INLINE V3<F> operator-(V3<F> a, V3<F> b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class F>
HWY_INLINE V3<F> operator*(V3<F> a, V3<F> b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <class F>
HWY_INLINE V3<F> operator*(V3<F> a, F s) {
    return {a.x * s, a.y * s, a.z * s};
}
template <class F>
HWY_INLINE F Dot(V3<F> a, V3<F> b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
// cross and normalize of math/vec3.h: the same operations in the same order.
template <class F>
HWY_INLINE V3<F> Cross(V3<F> a, V3<F> b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class L>
HWY_INLINE V3<typename L::F> Normalize(V3<typename L::F> a) {
    return a * (L::Set(1.0f) / L::Sqrt(Dot(a, a)));
}
template <class L>
HWY_INLINE V3<typename L::F> Neg3(V3<typename L::F> a) {
    return {L::Neg(a.x), L::Neg(a.y), L::Neg(a.z)};
}
// Per lane: yes where m, else no.
template <class L>
HWY_INLINE V3<typename L::F> Select3(typename L::M m, V3<typename L::F> yes, V3<typename L::F> no) {
    return {L::Select(m, yes.x, no.x), L::Select(m, yes.y, no.y), L::Select(m, yes.z, no.z)};
}

// A BSDF's value f and its density p where `valid`, else 0 and density 0: the value returned,
// the density in *pdf.
template <class L>
HWY_INLINE V3<typename L::F> ValueWhere(typename L::M valid,
                                        V3<typename L::F> f,
                                        typename L::F p,
                                        typename L::F* pdf) {
    const typename L::F zero = L::Set(0.0f);
    *pdf = L::Select(valid, p, zero);
    return Select3<L>(valid, f, V3<typename L::F>{zero, zero, zero});
}
template <class L>
HWY_INLINE typename L::F MaxComponent(V3<typename L::F> a) {
    return L::Max(L::Max(a.x, a.y), a.z);
}

inline V3<float> to_lanes(Vec3 v) {
    return {v.x, v.y, v.z};
}
inline Vec3 to_vec3(V3<float> v) {
    return {v.x, v.y, v.z};
}

// ---- formulas shared by several kernels ------------------------------------------------------

// sin and cos of 2 pi u for u in [0, 1]: u is reduced to the nearest quarter turn q / 4 (exactly,
// by Sterbenz's lemma), the remainder y = 2 pi (u - q / 4) in [-pi/4, pi/4] goes through Taylor
// polynomials of degree 9 and 8 (truncation below 3e-8, under an ulp), and the quarter turn
// rotates the pair. The same polynomial in every lane and in scalar code.
template <class L>
HWY_INLINE void SinCos2Pi(typename L::F u, typename L::F* sin_out, typename L::F* cos_out) {
    using F = typename L::F;
    const F q = L::Round(u * L::Set(4.0f));
    const F y = (u - q * L::Set(0.25f)) * L::Set(6.283185307179586f);
    const F y2 = y * y;
    const F s = y + y * y2 *
                        (L::Set(-1.0f / 6.0f) +
                         y2 * (L::Set(1.0f / 120.0f) +
                               y2 * (L::Set(-1.0f / 5040.0f) + y2 * L::Set(1.0f / 362880.0f))));
    const F c =
        L::Set(1.0f) +
        y2 * (L::Set(-0.5f) + y2 * (L::Set(1.0f / 24.0f) +
                                    y2 * (L::Set(-1.0f / 720.0f) + y2 * L::Set(1.0f / 40320.0f))));
    // Quarter turn k = q mod 4: (sin, cos) of y + k pi/2 is (s, c), (c, -s), (-s, -c), (-c, s).
    const auto is = [&](float k) { return q == L::Set(k); };
    const auto odd = L::Or(is(1.0f), is(3.0f));
    const F sin_r = L::Select(odd, c, s), cos_r = L::Select(odd, s, c);
    *sin_out = L::Select(L::Or(is(2.0f), is(3.0f)), L::Neg(sin_r), sin_r);
    *cos_out = L::Select(L::Or(is(1.0f), is(2.0f)), L::Neg(cos_r), cos_r);
}

// atan2(y, x) in (-pi, pi]: t = min(|x|, |y|) / max(|x|, |y|) in [0, 1], reduced further to
// |t'| <= tan(pi/8) by atan t = pi/4 + atan((t - 1) / (t + 1)) above tan(pi/8), then Cephes'
// atanf polynomial (S. Moshier; relative error below 2e-7), and the octant's symmetries:
// pi/2 - a where |y| > |x|, pi - a where x < 0, the sign of y. atan2(0, 0) = 0.
template <class L>
HWY_INLINE typename L::F Atan2(typename L::F y, typename L::F x) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F ay = L::Abs(y), ax = L::Abs(x);
    const F hi = L::Max(ax, ay), lo = L::Min(ax, ay);
    const F t = L::Select(hi > zero, lo / L::Select(hi > zero, hi, one), zero);
    const auto upper = t > L::Set(0.41421356237309503f);
    const F r = L::Select(upper, (t - one) / (t + one), t);
    const F z = r * r;
    const F poly =
        ((L::Set(8.05374449538e-2f) * z - L::Set(1.38776856032e-1f)) * z +
         L::Set(1.99777106478e-1f)) * z - L::Set(3.33329491539e-1f);
    F a = L::Select(upper, L::Set(0.78539816339744831f), zero) + (poly * z * r + r);
    a = L::Select(ay > ax, L::Set(1.5707963267948966f) - a, a);
    a = L::Select(x < zero, L::Set(3.1415926535897932f) - a, a);
    return L::CopySign(a, y);
}

// acos(c) for c in [-1, 1], as atan2(sqrt((1 - c)(1 + c)), c): accurate at both ends, where
// 1 - c^2 would cancel.
template <class L>
HWY_INLINE typename L::F Acos(typename L::F c) {
    const typename L::F one = L::Set(1.0f);
    return Atan2<L>(L::Sqrt((one - c) * (one + c)), c);
}

// Natural logarithm of a positive normal x: x = m 2^e with m in [sqrt(1/2), sqrt(2)), then
// log(m) = log(1 + f) from Cephes' logf polynomial (S. Moshier; relative error below 2e-7),
// and e log 2 added in two parts (0.693359375 is exact in float) so that it loses nothing.
template <class L>
HWY_INLINE typename L::F Log(typename L::F x) {
    using F = typename L::F;
    F m;
    F e = L::SplitExponent(x, &m);
    const auto high = m > L::Set(1.41421356f);
    m = L::Select(high, m * L::Set(0.5f), m);
    e = L::Select(high, e + L::Set(1.0f), e);
    const F f = m - L::Set(1.0f);
    const F z = f * f;
    F p = L::Set(7.0376836292e-2f);
    for (const float c : {-1.1514610310e-1f, 1.1676998740e-1f, -1.2420140846e-1f, 1.4249322787e-1f,
                          -1.6668057665e-1f, 2.0000714765e-1f, -2.4999993993e-1f, 3.3333331174e-1f})
        p = p * f + L::Set(c);
    F y = p * f * z;
    y = y + L::Set(-2.12194440e-4f) * e;
    y = y + L::Set(-0.5f) * z;
    return f + y + L::Set(0.693359375f) * e;
}

// e^x for x <= 88: x = n log 2 + r with |r| <= log(2) / 2 (log 2 in two parts, the first exact
// in float, so that r loses nothing), e^r from Cephes' expf polynomial (S. Moshier; relative
// error below 2e-7), times 2^n. Below -87.3 (2^-126) it is 0: no subnormal results.
template <class L>
HWY_INLINE typename L::F Exp(typename L::F x) {
    using F = typename L::F;
    const auto underflows = x < L::Set(-87.3f);
    x = L::Min(L::Max(x, L::Set(-87.3f)), L::Set(88.0f));
    const typename L::I k = L::Trunc(x * L::Set(1.44269504f) + L::CopySign(L::Set(0.5f), x));
    const F n = L::ToFloat(k);  // x / log 2 rounded to the nearest whole number
    const F r = x - n * L::Set(0.693359375f) - n * L::Set(-2.12194440e-4f);
    F p = L::Set(1.9875691500e-4f);
    for (const float c :
         {1.3981999507e-3f, 8.3334519073e-3f, 4.1665795894e-2f, 1.6666665459e-1f, 5.0000001201e-1f})
        p = p * r + L::Set(c);
    const F e = (p * (r * r) + r + L::Set(1.0f)) * L::Pow2(k);
    return L::Select(underflows, L::Set(0.0f), e);
}

// log(1 + x) for x > -1, accurate for small x too: with w = 1 + x rounded, log(w) x / (w - 1)
// cancels the rounding of w (Goldberg, "What Every Computer Scientist Should Know About
// Floating-Point Arithmetic", 1991, Theorem 4); x itself where w rounds to 1.
template <class L>
HWY_INLINE typename L::F Log1p(typename L::F x) {
    using F = typename L::F;
    const F w = L::Set(1.0f) + x;
    const auto tiny = w == L::Set(1.0f);
    const F d = L::Select(tiny, L::Set(1.0f), w - L::Set(1.0f));
    return L::Select(tiny, x, Log<L>(L::Select(tiny, L::Set(1.0f), w)) * x / d);
}

// -log(1 - u): an exponentially distributed optical depth from a uniform u in [0, 1), by
// inversion (the free flight of a path in a medium; pbrt-v4 SampleExponential).
template <class L>
HWY_INLINE typename L::F OpticalDepth(typename L::F u) {
    return L::Neg(Log1p<L>(L::Neg(u)));
}

// Orthonormal basis (s, t) completing the unit normal n, without branches on n's direction:
// Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
template <class L>
HWY_INLINE void OrthonormalBasis(V3<typename L::F> n, V3<typename L::F>* s, V3<typename L::F>* t) {
    using F = typename L::F;
    const F one = L::Set(1.0f);
    const F sign = L::CopySign(one, n.z);
    const F a = L::Neg(one) / (sign + n.z);
    const F b = n.x * n.y * a;
    *s = {one + sign * n.x * n.x * a, sign * b, L::Neg(sign * n.x)};
    *t = {b, sign + n.y * n.y * a, L::Neg(n.y)};
}

// Offset of ray origins from surfaces, relative to the point's magnitude (math/ray.h).
template <class L>
HWY_INLINE typename L::F OriginOffset(V3<typename L::F> p) {
    using F = typename L::F;
    const F m = L::Max(L::Max(L::Abs(p.x), L::Abs(p.y)), L::Abs(p.z));
    return L::Set(2e-5f) * (L::Set(1.0f) + m);
}

// A ray origin just off a surface at p (geometric normal ng) on the side the direction w leaves
// towards, so that the ray does not find the surface it starts on; p itself where ng = 0 (in a
// medium).
template <class L>
HWY_INLINE V3<typename L::F> OffsetRayOrigin(V3<typename L::F> p,
                                             V3<typename L::F> ng,
                                             V3<typename L::F> w) {
    const typename L::F eps = OriginOffset<L>(p);
    return p + ng * L::Select(Dot(w, ng) > L::Set(0.0f), eps, L::Neg(eps));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_MATH_LANES_INL_H_
