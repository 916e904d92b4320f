// The ray-sphere test (intersect_sphere, which runs the one-lane instance), written once over
// lanes for the light samples towards spheres (lights/sphere_light-inl.h). The BVH's block test
// (SphereLanes in wide_leaf_tests-inl.h) performs the same operations in the same order. Per-target
// header, see math/lanes-inl.h.
#if defined(WAVETRACE_ACCEL_SPHERE_HIT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_ACCEL_SPHERE_HIT_INL_H_
#undef WAVETRACE_ACCEL_SPHERE_HIT_INL_H_
#else
#define WAVETRACE_ACCEL_SPHERE_HIT_INL_H_
#endif

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Whether the ray o + t d meets the sphere (centre c, radius r) for t in [tmin, tmax], and the
// nearest such t. Solves a t^2 + 2 b t + c = 0 with f = o - centre, a = d.d, b = f.d,
// c = f.f - r^2; the quarter-discriminant b^2 - a c equals a (r^2 - |f - (b/a) d|^2), which does
// not cancel catastrophically when the ray passes far from the centre (RT Gems, eq. 7.5); stable
// roots q = -(b + sign(b) sqrt(disc)), t0 = c / q, t1 = q / a (eq. 7.8).
template <class L>
HWY_INLINE typename L::M SphereHit(V3<typename L::F> o,
                                   V3<typename L::F> d,
                                   V3<typename L::F> centre,
                                   typename L::F radius,
                                   typename L::F tmin,
                                   typename L::F tmax,
                                   typename L::F* t) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    const V3<F> f = o - centre;
    const F a = Dot(d, d);
    const F b = Dot(f, d);
    const F c = Dot(f, f) - radius * radius;
    const V3<F> l = f - d * (b / a);
    const F disc = a * (radius * radius - Dot(l, l));
    const auto meets = L::Not(disc < zero);
    const F q = L::Neg(b + L::CopySign(L::Sqrt(L::Max(disc, zero)), b));
    const auto q_zero = q == zero;
    const F t0 = L::Select(q_zero, zero, c / L::Select(q_zero, L::Set(1.0f), q));
    const F t1 = q / a;
    // The nearer root first (a swap when t0 > t1).
    const F lo = L::Min(t0, t1), hi = L::Max(t1, t0);
    const auto lo_in = L::And(L::Not(lo < tmin), L::Not(lo > tmax));
    const auto hi_in = L::And(L::Not(hi < tmin), L::Not(hi > tmax));
    *t = L::Select(lo_in, lo, hi);
    return L::And(meets, L::Or(lo_in, hi_in));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_ACCEL_SPHERE_HIT_INL_H_
