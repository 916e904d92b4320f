// The Dirac-delta lobes of lane vertices over lanes, each lane of its own: a mirror (weight the
// albedo), a smooth metal (Schlick's Fresnel with the albedo as F0), a smooth conductor (the
// albedo times the Fresnel of eta + ik) and a smooth dielectric (reflection with Fresnel's
// probability, weight 1, else refraction, weight 1 / eta^2: radiance is compressed entering a
// denser medium, Veach 1997, §5.2), in the shading frame or in world directions about the
// shading normal; bsdf_sample runs the one-lane instance. Per-target header, see
// math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_SPECULAR_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_SPECULAR_INL_H_
#undef WAVETRACE_BSDFS_SPECULAR_INL_H_
#else
#define WAVETRACE_BSDFS_SPECULAR_INL_H_
#endif

#include "bsdfs/conductor-inl.h"
#include "bsdfs/dielectric-inl.h"
#include "bsdfs/glossy-inl.h"
#include "bsdfs/metal-inl.h"
#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The delta lobe's direction and weight for wo in the shading frame, in the lanes of b.delta
// (their kind by b's metal, conductor and dielectric masks, none: a mirror; a conductor's eta
// and k, a dielectric's index in eta.x); pdf 0. Not valid where wo is tangent to the shading
// surface.
template <class L>
HWY_INLINE GlossyLobeSample<L> SpecularLocal(const LaneBsdf<L>& b,
                                             V3<typename L::F> wo,
                                             typename L::F u_lobe) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F side = SideOf<L>(wo);
    const F cos_i = L::Abs(wo.z);
    V3<F> wi{L::Neg(wo.x), L::Neg(wo.y), wo.z};
    V3<F> weight = b.albedo;
    GlossyLobeSample<L> s;
    s.transmitted = L::Not(L::All());
    if (L::Any(b.metal)) weight = Select3<L>(b.metal, Schlick<L>(b.albedo, wo.z * side), weight);
    if (L::Any(b.conductor))
        weight = Select3<L>(b.conductor, b.albedo * FresnelConductor<L>(cos_i, b.eta, b.k), weight);
    if (L::Any(b.dielectric)) {
        const F eta = SeenEta<L>(b.eta.x, wo.z);
        const F f = FresnelDielectric<L>(cos_i, eta);
        s.transmitted = L::AndNot(u_lobe < f, b.dielectric);
        // Snell: wt = -wo / eta + (cos_i / eta - cos_t) n, n on wo's side.
        const F cos_t = L::Sqrt(L::Max(zero, one - (one - cos_i * cos_i) / (eta * eta)));
        const V3<F> refracted = Normalize<L>(Neg3<L>(wo) * (one / eta) +
                                             V3<F>{zero, zero, side * (cos_i / eta - cos_t)});
        wi = Select3<L>(s.transmitted, refracted, wi);
        const F w = one / (eta * eta);
        weight = Select3<L>(
            b.dielectric, Select3<L>(s.transmitted, V3<F>{w, w, w}, V3<F>{one, one, one}), weight);
    }
    s.valid = wo.z != zero;
    s.wi = wi;
    s.weight = weight;
    s.pdf = zero;
    return s;
}

// SpecularLocal for world directions about the shading normal ns.
template <class L>
HWY_INLINE GlossyLobeSample<L> SpecularSample(const LaneBsdf<L>& b,
                                              V3<typename L::F> ns,
                                              V3<typename L::F> wo,
                                              typename L::F u_lobe) {
    const GlossyFrame<L> frame(ns);
    GlossyLobeSample<L> s = SpecularLocal<L>(b, frame.ToLocal(wo), u_lobe);
    s.wi = frame.ToWorld(s.wi);
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_SPECULAR_INL_H_
