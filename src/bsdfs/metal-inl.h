// The GGX microfacet metal (Trowbridge-Reitz distribution, height-correlated Smith masking,
// Schlick's Fresnel with the albedo as F0, visible-normal sampling), written once over lanes:
// bsdf_eval / bsdf_pdf / bsdf_sample run the one-lane instances for both engines; the
// wavefront's shade kernel runs them over the metal vertices of a chunk
// (blocks/lane_kernels.cpp). Also what the other reflecting lobes share: Schlick's
// approximation, the mirror about a microfacet normal, the reflection sample. Directions are in
// the shading frame, z along the normal. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_METAL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_METAL_INL_H_
#undef WAVETRACE_BSDFS_METAL_INL_H_
#else
#define WAVETRACE_BSDFS_METAL_INL_H_
#endif

#include "math/lanes-inl.h"
#include "microfacets/ggx-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Schlick's weight (1 - cos theta)^5, cos theta clamped to [0, 1] (Schlick 1994).
template <class L>
HWY_INLINE typename L::F SchlickWeight(typename L::F cos_theta) {
    using F = typename L::F;
    const F one = L::Set(1.0f);
    const F m = L::Min(L::Max(one - cos_theta, L::Set(0.0f)), one);
    return (m * m) * (m * m) * m;
}

// Schlick's approximation with the albedo as the reflectance at normal incidence: Ray Tracing in
// One Weekend's metal tint, made angle-dependent.
template <class L>
HWY_INLINE V3<typename L::F> Schlick(V3<typename L::F> f0, typename L::F cos_theta) {
    using F = typename L::F;
    const F one = L::Set(1.0f);
    return f0 + V3<F>{one - f0.x, one - f0.y, one - f0.z} * SchlickWeight<L>(cos_theta);
}

// Both directions mirrored into the upper hemisphere when wo is below (two-sided shading).
template <class L>
HWY_INLINE V3<typename L::F> Upper(V3<typename L::F> w, typename L::F side) {
    return {w.x, w.y, w.z * side};
}
template <class L>
HWY_INLINE typename L::F SideOf(V3<typename L::F> wo) {
    return L::Select(wo.z < L::Set(0.0f), L::Set(-1.0f), L::Set(1.0f));
}

// f |cos theta_i| and the density of sampling wi, for wo and wi on one side (else 0, 0), of a
// metal of roughness alpha > 0.
template <class L>
HWY_INLINE V3<typename L::F> MetalEval(V3<typename L::F> albedo,
                                       typename L::F alpha,
                                       V3<typename L::F> wo,
                                       V3<typename L::F> wi,
                                       typename L::F* pdf) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const auto valid = L::Not(wo.z * wi.z <= zero);
    const F side = SideOf<L>(wo);
    const V3<F> o = Upper<L>(wo, side), i = Upper<L>(wi, side);
    const V3<F> h = Normalize<L>(o + i);
    const F d = GgxD<L>(h.z, alpha);
    // Visible-normal density D_o(h) = G1(o) D(h) (o.h) / o.z, times the reflection Jacobian
    // 1 / (4 o.h); f cos_i = F D G2 / (4 cos_o), with the height-correlated Smith G2.
    const F p = GgxG1<L>(o.z, alpha) * d / (L::Set(4.0f) * o.z);
    const F g2 = one / (one + GgxLambda<L>(o.z, alpha) + GgxLambda<L>(i.z, alpha));
    const V3<F> f = Schlick<L>(albedo, Dot(i, h)) * (d * g2 / (L::Set(4.0f) * o.z));
    return ValueWhere<L>(valid, f, p, pdf);
}

// o reflected about the microfacet normal m: 2 (o.m) m - o.
template <class L>
HWY_INLINE V3<typename L::F> Reflect(V3<typename L::F> o, V3<typename L::F> m) {
    return m * (L::Set(2.0f) * Dot(o, m)) - o;
}

// A direction sampled from a reflecting microfacet lobe (a metal's, a conductor's).
template <class L>
struct ReflectionSample {
    typename L::M valid;       // false: wo grazing, or reflected below the surface
    V3<typename L::F> wi;      // on wo's side
    V3<typename L::F> weight;  // f |cos| / pdf
    typename L::F pdf;
};

// A direction sampled by the visible normals, for a metal of roughness alpha > 0: weight
// F G2 / G1(o). The pdf and
// weight are recomputed from (o, i) as MetalEval computes them, so that they agree with it to
// the last bit (MIS relies on it).
template <class L>
HWY_INLINE ReflectionSample<L> MetalSample(V3<typename L::F> albedo,
                                           typename L::F alpha,
                                           V3<typename L::F> wo,
                                           typename L::F u1,
                                           typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    ReflectionSample<L> s;
    const F side = SideOf<L>(wo);
    const V3<F> o = Upper<L>(wo, side);
    const V3<F> m = GgxVisibleNormal<L>(o, alpha, alpha, u1, u2);
    const V3<F> i = Reflect<L>(o, m);
    const V3<F> h = Normalize<L>(o + i);
    const F g1 = GgxG1<L>(o.z, alpha);
    s.pdf = g1 * GgxD<L>(h.z, alpha) / (L::Set(4.0f) * o.z);
    const F g2 = one / (one + GgxLambda<L>(o.z, alpha) + GgxLambda<L>(i.z, alpha));
    s.weight = Schlick<L>(albedo, Dot(i, h)) * (g2 / g1);
    s.wi = Upper<L>(i, side);
    s.valid = L::And(L::And(L::Not(wo.z == zero), i.z > zero), s.pdf > zero);
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_METAL_INL_H_
