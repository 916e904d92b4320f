// Clarberg's equal-area octahedral mapping (math/equal_area.h has the layout) written once over
// lanes: the scalar equal_area_* functions are its one-lane instances, the wavefront's
// environment lookups run it in SIMD lanes. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_MATH_EQUAL_AREA_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_MATH_EQUAL_AREA_INL_H_
#undef WAVETRACE_MATH_EQUAL_AREA_INL_H_
#else
#define WAVETRACE_MATH_EQUAL_AREA_INL_H_
#endif

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// (u, v) in [0, 1]^2 to a unit direction. In the square's coordinates a = 2u - 1, b = 2v - 1,
// the L1 distance s = |a| + |b| from the centre gives the polar distance: r = s inside the
// diamond s <= 1 (z >= 0), r = 2 - s outside it (the four corner triangles folded over to
// z < 0), with |z| = 1 - r^2 so that areas are kept; the position along the diamond's edge
// gives the azimuth within the quadrant, phi = pi/4 ((|b| - |a|) / r + 1), and the signs of a
// and b the quadrant.
template <class L>
HWY_INLINE V3<typename L::F> EqualAreaSquareToSphere(typename L::F u, typename L::F v) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f), two = L::Set(2.0f);
    const F a = two * u - one, b = two * v - one;
    const F signed_distance = one - (L::Abs(a) + L::Abs(b));
    const F r = one - L::Abs(signed_distance);
    const auto centre = r == zero;
    // phi / (2 pi) = ((|b| - |a|) / r + 1) / 8, in [0, 1/4].
    const F turns =
        L::Select(centre, one, (L::Abs(b) - L::Abs(a)) / L::Select(centre, one, r) + one) *
        L::Set(0.125f);
    F sin_phi, cos_phi;
    SinCos2Pi<L>(turns, &sin_phi, &cos_phi);
    const F z = L::CopySign(one - r * r, signed_distance);
    const F planar = r * L::Sqrt(L::Max(zero, two - r * r));
    return {L::CopySign(cos_phi, a) * planar, L::CopySign(sin_phi, b) * planar, z};
}

// A unit direction to (u, v) in [0, 1]^2; the inverse of the above.
template <class L>
HWY_INLINE void EqualAreaSphereToSquare(V3<typename L::F> d, typename L::F* u, typename L::F* v) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f), half = L::Set(0.5f);
    const F x = L::Abs(d.x), y = L::Abs(d.y), z = L::Abs(d.z);
    // r = sqrt(1 - |z|), written so that it keeps its precision near the poles.
    const F r = L::Sqrt((x * x + y * y) / (one + z));
    const F t = Atan2<L>(y, x) * L::Set(0.63661977236758134f);  // the azimuth in the quadrant
    const F b_in = r * t, a_in = r - b_in;                      // on the diamond |a| + |b| = r
    // Below the equator, folded out to |a| + |b| = 2 - r.
    const auto below = d.z < zero;
    const F a = L::CopySign(L::Select(below, one - b_in, a_in), d.x);
    const F b = L::CopySign(L::Select(below, one - a_in, b_in), d.y);
    *u = L::Min(L::Max(half * (a + one), zero), one);
    *v = L::Min(L::Max(half * (b + one), zero), one);
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_MATH_EQUAL_AREA_INL_H_
