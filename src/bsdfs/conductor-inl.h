// The conductor's Fresnel reflectance and its rough reflection over lanes: the formulas of
// conductor.h and fresnel.h, which run their one-lane instances. Per-target header, see
// math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_CONDUCTOR_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_CONDUCTOR_INL_H_
#undef WAVETRACE_BSDFS_CONDUCTOR_INL_H_
#else
#define WAVETRACE_BSDFS_CONDUCTOR_INL_H_
#endif

#include "bsdfs/metal-inl.h"
#include "math/lanes-inl.h"
#include "microfacets/microfacet-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The unpolarized reflectance of one channel, complex index of refraction n = eta + i k, at
// cos theta = c in [0, 1] (Born & Wolf, Principles of Optics, §14.2): with w = a + i b =
// sqrt(n^2 - sin^2 theta), r_s = (c - w) / (c + w) and r_p = (n^2 c - w) / (n^2 c + w), so
//   |r_s|^2 = ((c - a)^2 + b^2) / ((c + a)^2 + b^2),
//   |r_p|^2 = ((P c - a)^2 + (Q c - b)^2) / ((P c + a)^2 + (Q c + b)^2), n^2 = P + i Q,
// sums of squares that float keeps to its precision (the expanded form a^2 + b^2 - 2 a c + c^2
// loses digits where |w| is large). The complex square root takes its larger part from a real
// root and the other as Im / (2 x) (no cancellation). 1 at grazing incidence onto n = 1.
template <class L>
HWY_INLINE typename L::F FresnelConductorChannel(typename L::F c,
                                                 typename L::F eta,
                                                 typename L::F k) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f), half = L::Set(0.5f);
    const F p = eta * eta - k * k, q = L::Set(2.0f) * eta * k;
    const F x = p - (one - c * c);  // n^2 - sin^2: x + i q, q >= 0
    const F r = L::Sqrt(x * x + q * q);
    const F t = L::Sqrt(half * (r + L::Abs(x)));
    const F other = L::Select(t > zero, q / (L::Set(2.0f) * L::Select(t > zero, t, one)), zero);
    const auto positive = x >= zero;
    const F a = L::Select(positive, t, other), b = L::Select(positive, other, t);
    const F s_den = (c + a) * (c + a) + b * b;
    const F rs = ((c - a) * (c - a) + b * b) / L::Select(s_den > zero, s_den, one);
    const F pc = p * c, qc = q * c;
    const F p_den = (pc + a) * (pc + a) + (qc + b) * (qc + b);
    const F rp = ((pc - a) * (pc - a) + (qc - b) * (qc - b)) / L::Select(p_den > zero, p_den, one);
    return L::Select(s_den > zero, half * (rs + rp), one);
}

template <class L>
HWY_INLINE V3<typename L::F> FresnelConductor(typename L::F cos_i,
                                              V3<typename L::F> eta,
                                              V3<typename L::F> k) {
    const typename L::F c = L::Min(L::Max(cos_i, L::Set(0.0f)), L::Set(1.0f));
    return {FresnelConductorChannel<L>(c, eta.x, k.x), FresnelConductorChannel<L>(c, eta.y, k.y),
            FresnelConductorChannel<L>(c, eta.z, k.z)};
}

// A rough conductor: reflectance R, complex index eta + i k, its microfacet distribution.
template <class L>
struct RoughConductor {
    V3<typename L::F> reflectance, eta, k;
    MicrofacetLanes<L> md;
};

// f cos_i = R F(o.h) D(h) G2(o, i) / (4 cos_o) and the visible-normal density G1(o) D(h) /
// (4 cos_o) of o and i above the surface (Walter et al. 2007, eq. 20), h = (o + i) / |o + i|.
template <class L>
HWY_INLINE V3<typename L::F> RoughConductorUpper(const RoughConductor<L>& c,
                                                 V3<typename L::F> o,
                                                 V3<typename L::F> i,
                                                 typename L::F* pdf) {
    using F = typename L::F;
    const F one = L::Set(1.0f), four_cos = L::Set(4.0f) * o.z;
    const V3<F> h = Normalize<L>(o + i);
    const F d = MicrofacetD<L>(c.md, h);
    const F lambda_o = MicrofacetLambda<L>(c.md, o);
    *pdf = d / ((one + lambda_o) * four_cos);
    const F g2 = one / (one + lambda_o + MicrofacetLambda<L>(c.md, i));
    return c.reflectance * FresnelConductor<L>(Dot(o, h), c.eta, c.k) * (d * g2 / four_cos);
}

// The same for any wo, wi: both sides reflect (from behind, wo.z < 0, the lobe is mirrored
// below the surface); 0 and density 0 for wo and wi on opposite sides or no density.
template <class L>
HWY_INLINE V3<typename L::F> RoughConductorEval(const RoughConductor<L>& c,
                                                V3<typename L::F> wo,
                                                V3<typename L::F> wi,
                                                typename L::F* pdf) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    const F side = SideOf<L>(wo);
    F p;
    const V3<F> f = RoughConductorUpper<L>(c, Upper<L>(wo, side), Upper<L>(wi, side), &p);
    return ValueWhere<L>(L::And(wo.z * wi.z > zero, p > zero), f, p, pdf);
}

// A direction by the visible normals of wo mirrored above the surface; its value and density
// from (o, i) as RoughConductorEval computes them, so that weight = eval / pdf.
template <class L>
HWY_INLINE ReflectionSample<L> RoughConductorSample(const RoughConductor<L>& c,
                                                    V3<typename L::F> wo,
                                                    typename L::F u1,
                                                    typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    ReflectionSample<L> s;
    const F side = SideOf<L>(wo);
    const V3<F> o = Upper<L>(wo, side);
    const V3<F> m = MicrofacetVisibleNormal<L>(c.md, o, u1, u2);
    const V3<F> i = Reflect<L>(o, m);
    const V3<F> f = RoughConductorUpper<L>(c, o, i, &s.pdf);
    s.valid = L::And(L::And(L::Not(wo.z == zero), i.z > zero), s.pdf > zero);
    s.weight = f * (one / L::Select(s.valid, s.pdf, one));
    s.wi = Upper<L>(i, side);
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_CONDUCTOR_INL_H_
