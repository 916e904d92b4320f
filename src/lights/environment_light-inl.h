// The environment map as a light, written once over lanes: a direction sampled by the map's
// distribution (LightSet's, over its texels) with its radiance and density, the density of any
// direction, and what a ray that leaves the scene finds. LightSet and resolve_segment run the
// one-lane instances (and with them the megakernel), the wavefront's light_sample and shade
// kernels the same formulas in SIMD lanes. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_LIGHTS_ENVIRONMENT_LIGHT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_LIGHTS_ENVIRONMENT_LIGHT_INL_H_
#undef WAVETRACE_LIGHTS_ENVIRONMENT_LIGHT_INL_H_
#else
#define WAVETRACE_LIGHTS_ENVIRONMENT_LIGHT_INL_H_
#endif

#include "lights/light_sample-inl.h"
#include "math/lanes-inl.h"
#include "sampling/distribution-inl.h"
#include "scene/environment-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The direction to the map at its sample (u, v) of density pdf_uv on the unit square
// (SampleDistribution2D's), the radiance there, and the solid-angle density pdf_uv / Jacobian
// times the selection probability; valid where that density is finite and positive and
// radiance arrives.
template <class L>
HWY_INLINE LightPoint<L> EnvironmentLightPointAt(const EnvironmentView& e,
                                                 typename L::F u,
                                                 typename L::F v,
                                                 typename L::F pdf_uv,
                                                 typename L::F select_prob) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    F jacobian;
    LightPoint<L> r;
    r.wi = EnvironmentDirection<L>(e, u, v, &jacobian);
    r.dist = L::Set(kInfinity);
    r.pdf = pdf_uv / jacobian * select_prob;
    r.radiance = EnvironmentRadiance<L>(e, u, v);
    r.valid = L::And(L::And(jacobian > zero, L::IsFinite(r.pdf)), r.pdf > zero);
    r.valid = L::And(r.valid, MaxComponent<L>(r.radiance) > zero);
    return r;
}

// A direction to the map from u1, u2: (u, v) from the texels' distribution, then as
// EnvironmentLightPointAt.
template <class L>
HWY_INLINE LightPoint<L> EnvironmentLightPoint(const EnvironmentView& e,
                                               const Distribution2DTables& t,
                                               typename L::F u1,
                                               typename L::F u2,
                                               typename L::F select_prob) {
    typename L::F u, v;
    const typename L::F pdf_uv = SampleDistribution2D<L>(t, u1, u2, &u, &v);
    return EnvironmentLightPointAt<L>(e, u, v, pdf_uv, select_prob);
}

// The solid-angle density with which EnvironmentLightPoint produces the direction at the map's
// (u, v), before the selection probability: p(u, v) / Jacobian, 0 at the poles of a lat-long
// map.
template <class L>
HWY_INLINE typename L::F EnvironmentPdfAt(const EnvironmentView& e,
                                          const Distribution2DTables& t,
                                          typename L::F u,
                                          typename L::F v) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    const F jacobian = EnvironmentJacobian<L>(e, v);
    const auto positive = jacobian > zero;
    return L::Select(positive,
                     Distribution2DPdf<L>(t, u, v) / L::Select(positive, jacobian, L::Set(1.0f)),
                     zero);
}

// The same for the unit world direction w.
template <class L>
HWY_INLINE typename L::F EnvironmentPdf(const EnvironmentView& e,
                                        const Distribution2DTables& t,
                                        V3<typename L::F> w) {
    typename L::F u, v;
    EnvironmentUv<L>(e, w, &u, &v);
    return EnvironmentPdfAt<L>(e, t, u, v);
}

// What a ray that leaves the scene towards the map's (u, v) (EnvironmentUvOfRay) finds: the
// map's radiance and, with_pdf, the density with which the light sample of the vertex it left
// would have chosen its direction (selection included), which MIS weighs the radiance by.
template <class L>
struct EscapedRay {
    V3<typename L::F> radiance;
    typename L::F pdf_light;
};
template <class L>
HWY_INLINE EscapedRay<L> Escape(const EnvironmentView& e,
                                const Distribution2DTables& t,
                                typename L::F u,
                                typename L::F v,
                                typename L::F select_prob,
                                bool with_pdf) {
    EscapedRay<L> r;
    r.radiance = EnvironmentRadiance<L>(e, u, v);
    r.pdf_light = with_pdf ? select_prob * EnvironmentPdfAt<L>(e, t, u, v) : L::Set(0.0f);
    return r;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_LIGHTS_ENVIRONMENT_LIGHT_INL_H_
