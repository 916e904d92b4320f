// The two diffuse lobes, written once over lanes: Lambertian reflection and the isotropic phase
// function, each's f |cos| and density. bsdf_eval / bsdf_pdf / bsdf_sample run the one-lane
// instances, the light samples and the continuations of lane vertices (light_sample-inl.h,
// surface_step-inl.h) the same templates, so that the density a light sample reports for the
// BSDF is the one a BSDF sample of that direction has. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_DIFFUSE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_DIFFUSE_INL_H_
#undef WAVETRACE_BSDFS_DIFFUSE_INL_H_
#else
#define WAVETRACE_BSDFS_DIFFUSE_INL_H_
#endif

#include "math/lanes-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The cosine hemisphere's density of a direction whose cosine with the shading normal is wi_z:
// |cos theta_i| / pi.
template <class L>
HWY_INLINE typename L::F LambertianPdf(typename L::F wi_z) {
    return L::Set(kInvPi) * L::Abs(wi_z);
}

// Lambertian f |cos theta_i| = albedo |cos theta_i| / pi, and its density, where wo and wi (their
// cosines with the shading normal: wo_z, wi_z) lie on one side of the shading surface; else 0.
template <class L>
HWY_INLINE V3<typename L::F> LambertianEval(V3<typename L::F> albedo,
                                            typename L::F wo_z,
                                            typename L::F wi_z,
                                            typename L::F* pdf) {
    const typename L::F zero = L::Set(0.0f);
    *pdf = L::Select(wo_z * wi_z > zero, LambertianPdf<L>(wi_z), zero);
    return albedo * *pdf;
}

// The isotropic phase function's density, that of a uniform direction: 1 / (4 pi).
template <class L>
HWY_INLINE typename L::F PhasePdf() {
    return L::Set(0.25f * kInvPi);
}

// The isotropic phase function f = albedo / (4 pi) ("cos" is 1 in a medium), and its density.
template <class L>
HWY_INLINE V3<typename L::F> PhaseEval(V3<typename L::F> albedo, typename L::F* pdf) {
    *pdf = PhasePdf<L>();
    return albedo * *pdf;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_DIFFUSE_INL_H_
