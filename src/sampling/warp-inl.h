// Warps from [0,1)^2 to directions over lanes (sampling/warp.h has the scalar ones, some of
// which are the one-lane instances of these). Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_SAMPLING_WARP_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SAMPLING_WARP_INL_H_
#undef WAVETRACE_SAMPLING_WARP_INL_H_
#else
#define WAVETRACE_SAMPLING_WARP_INL_H_
#endif

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Cosine-weighted hemisphere by Malley's method: a uniform disk point lifted to the hemisphere.
// pdf = cos(theta) / pi.
template <class L>
HWY_INLINE V3<typename L::F> CosineHemisphere(typename L::F u1, typename L::F u2) {
    typename L::F sin_phi, cos_phi;
    SinCos2Pi<L>(u2, &sin_phi, &cos_phi);
    const typename L::F r = L::Sqrt(u1);
    return {r * cos_phi, r * sin_phi, L::Sqrt(L::Max(L::Set(0.0f), L::Set(1.0f) - u1))};
}

// Uniform on the unit sphere (Archimedes: z uniform in [-1, 1]). pdf = 1 / (4 pi).
template <class L>
HWY_INLINE V3<typename L::F> UniformSphere(typename L::F u1, typename L::F u2) {
    typename L::F sin_phi, cos_phi;
    SinCos2Pi<L>(u2, &sin_phi, &cos_phi);
    const typename L::F z = L::Set(1.0f) - L::Set(2.0f) * u1;
    const typename L::F r = L::Sqrt(L::Max(L::Set(0.0f), L::Set(1.0f) - z * z));
    return {r * cos_phi, r * sin_phi, z};
}

// A density per unit area turned into one per unit solid angle at a point distance^2 = dist2
// away, seen at |cos theta| = cos_l from the surface's normal: p_w = p_A r^2 / |cos theta|
// (Veach 1997, eq. 8.10), here for the uniform density 1 / area.
template <class L>
HWY_INLINE typename L::F UniformAreaToSolidAngle(typename L::F dist2,
                                                 typename L::F cos_l,
                                                 typename L::F area) {
    return dist2 / (cos_l * area);
}
}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SAMPLING_WARP_INL_H_
