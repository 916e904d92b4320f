// The Beckmann microfacet distribution, anisotropic with roughness alpha_u along the shading
// frame's x axis and alpha_v along its y: its density, Smith's Lambda and the sampling of its
// visible normals, written once over lanes (MicrofacetDistribution runs the one-lane
// instances). Directions are unit vectors in the shading frame, z along the normal. In float,
// with the exponential and error functions of math/: against libm in double they agree to
// about 1e-7 (tests/test_bsdf.cpp). Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_MICROFACETS_BECKMANN_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_MICROFACETS_BECKMANN_INL_H_
#undef WAVETRACE_MICROFACETS_BECKMANN_INL_H_
#else
#define WAVETRACE_MICROFACETS_BECKMANN_INL_H_
#endif

#include "math/erf-inl.h"
#include "math/lanes-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

inline constexpr float kInvSqrtPi = 0.564189584f;

// D(m) = exp(-(mx^2/au^2 + my^2/av^2) / mz^2) / (pi au av mz^4); 0 for mz <= 0.
template <class L>
HWY_INLINE typename L::F BeckmannD(V3<typename L::F> m, typename L::F au, typename L::F av) {
    using F = typename L::F;
    const auto below = m.z <= L::Set(0.0f);
    const F z2 = L::Select(below, L::Set(1.0f), m.z * m.z);
    const F xu = m.x / au, yv = m.y / av;
    const F d = Exp<L>(L::Neg((xu * xu + yv * yv) / z2)) / (L::Set(kPi) * au * av * z2 * z2);
    return L::Select(below, L::Set(0.0f), d);
}

// Smith's Lambda (Heitz 2014, "Understanding the Masking-Shadowing Function", §5.2): with
// a = |w.z| / sqrt(au^2 wx^2 + av^2 wy^2) = 1 / (alpha tan theta) along w's azimuth,
// (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi)) = exp(-a^2) (1 / (a sqrt(pi)) - erfc(a) e^(a^2))
// / 2; 0 along the normal, infinite at grazing.
template <class L>
HWY_INLINE typename L::F BeckmannLambda(V3<typename L::F> w, typename L::F au, typename L::F av) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    const F x = au * w.x, y = av * w.y;
    const F r2 = x * x + y * y;
    const auto normal = r2 <= zero, grazing = w.z * w.z <= zero;
    const F a = L::Abs(w.z) / L::Sqrt(L::Select(normal, L::Set(1.0f), r2));
    const F safe_a = L::Select(grazing, L::Set(1.0f), a);
    const F lambda = L::Set(0.5f) * Exp<L>(L::Neg(safe_a * safe_a)) *
                     (L::Set(kInvSqrtPi) / safe_a - ErfcOverGaussian<L>(safe_a));
    return L::Select(normal, zero, L::Select(grazing, L::Set(kInfinity), L::Max(zero, lambda)));
}

// The slopes (x, y) of a visible normal of the unit-roughness Beckmann distribution seen from a
// direction at angle theta to the normal and azimuth 0. The visible slopes have density
// proportional to (cot theta - x) exp(-x^2 - y^2) for x < cot theta (Heitz & d'Eon 2014,
// "Importance Sampling Microfacet-Based BSDFs using the Distribution of Visible Normals", §4):
// y is a normal deviate, and x inverts the CDF
//   C(x) = (erfc(-x) + tan theta exp(-x^2) / sqrt(pi)) / (erfc(-cot theta) + tan theta
//          exp(-cot^2 theta) / sqrt(pi)),
// increasing for x < cot theta with C'(x) proportional to exp(-x^2) (1 - x tan theta): by
// Newton's method on x, kept inside a bisection bracket, from x = erfinv(b) with b what C would
// be without its tan theta terms, until a step moves x by less than 2^-18 of it. Lanes that
// converge keep their x while the others go on, so each lane's x is the one-lane instance's.
template <class L>
HWY_INLINE void BeckmannVisibleSlopes(typename L::F cos_theta,
                                      typename L::F sin_theta,
                                      typename L::F u1,
                                      typename L::F u2,
                                      typename L::F* x,
                                      typename L::F* y) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f), two = L::Set(2.0f);
    *y = ErfInv<L>(two * u2 - one);
    // At normal incidence the visible slopes are the slopes' own distribution.
    const auto normal = sin_theta < L::Set(1e-6f) * cos_theta;
    const F s = L::Select(normal, one, sin_theta);
    const F tan_theta = s / cos_theta, cot_theta = cos_theta / s;
    const F g_cot = Exp<L>(L::Neg(cot_theta * cot_theta));
    const F erfc_neg_cot = two - ErfcOverGaussian<L>(cot_theta) * g_cot;  // 1 + erf(cot)
    const F norm = one / (erfc_neg_cot + tan_theta * g_cot * L::Set(kInvSqrtPi));
    // C(-9) < 1e-35: below any u1 a float holds but 0.
    F lo = L::Set(-9.0f), hi = cot_theta;
    F t = L::Min(L::Max(ErfInv<L>(erfc_neg_cot * u1 - one), lo), hi);
    auto active = L::Not(normal);
    for (int i = 0; i < 16 && L::Any(active); ++i) {
        const F g = Exp<L>(L::Neg(t * t));
        const F q = ErfcOverGaussian<L>(L::Abs(t)) * g;
        const F erfc_neg_t = L::Select(t < zero, q, two - q);
        const F value = norm * (erfc_neg_t + tan_theta * g * L::Set(kInvSqrtPi)) - u1;
        const auto above = value > zero;
        hi = L::Select(L::And(active, above), t, hi);
        lo = L::Select(L::AndNot(above, active), t, lo);
        const F slope = norm * L::Set(2.0f * kInvSqrtPi) * g * (one - t * tan_theta);
        const F delta = value / slope;
        const F step = t - delta;
        // A Newton step this small is the last one: the next would be below float noise.
        const F tolerance = L::Set(0x1p-18f) * L::Max(one, L::Abs(t));
        const auto converged = L::Abs(delta) <= tolerance;
        const auto inside = L::And(step > lo, step < hi);
        const F next = L::Select(L::Or(converged, inside), step, L::Set(0.5f) * (lo + hi));
        t = L::Select(active, next, t);
        active = L::AndNot(L::Or(converged, hi - lo <= tolerance), active);
    }
    *x = L::Any(normal) ? L::Select(normal, ErfInv<L>(two * u1 - one), t) : t;
}

// A normal drawn with the density of visible normals from o (o.z > 0), G1(o) max(0, o.m) D(m)
// / o.z: stretch o to unit roughness, draw the slopes of the visible normals there, rotate them
// to the stretched o's azimuth and unstretch; slopes (x, y) are the normal (-x, -y, 1).
template <class L>
HWY_INLINE V3<typename L::F> BeckmannVisibleNormal(
    V3<typename L::F> o, typename L::F au, typename L::F av, typename L::F u1, typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F sx = au * o.x, sy = av * o.y;
    const F sxy = L::Sqrt(sx * sx + sy * sy);
    const F len = L::Sqrt(sx * sx + sy * sy + o.z * o.z);
    F x, y;
    BeckmannVisibleSlopes<L>(o.z / len, sxy / len, u1, u2, &x, &y);
    const auto tilted = sxy > zero;
    const F inv = one / L::Select(tilted, sxy, one);
    const F cos_phi = L::Select(tilted, sx * inv, one), sin_phi = L::Select(tilted, sy * inv, zero);
    const F rx = (cos_phi * x - sin_phi * y) * au;
    const F ry = (sin_phi * x + cos_phi * y) * av;
    const F n = one / L::Sqrt(rx * rx + ry * ry + one);
    return {L::Neg(rx) * n, L::Neg(ry) * n, n};
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_MICROFACETS_BECKMANN_INL_H_
