// A pixel reconstruction filter sampled by importance: offsets from a pixel's centre
// distributed as the filter, one axis at a time (the filters are separable), by inverting their
// distribution functions over lanes. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_
#undef WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_
#else
#define WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_
#endif

#include "math/erf-inl.h"
#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The tent r - |x| on [-r, r]: with t = 2u - 1, its inverse distribution function is
// sign(t) r (1 - sqrt(1 - |t|)).
template <class L>
HWY_INLINE typename L::F TentOffset(typename L::F u, float radius) {
    using F = typename L::F;
    const F t = L::Set(2.0f) * u - L::Set(1.0f);
    const F a = L::Set(radius) * (L::Set(1.0f) - L::Sqrt(L::Max(L::Set(0.0f), L::Set(1.0f) - L::Abs(t))));
    return L::CopySign(a, t);
}

// The Gaussian of deviation sigma truncated to [-r, r]: its distribution function maps u to
// sigma sqrt(2) erfinv((2u - 1) erf(r / (sigma sqrt 2))); `erf_radius` is that last factor.
template <class L>
HWY_INLINE typename L::F GaussianOffset(typename L::F u, float sigma, float erf_radius) {
    const typename L::F x = (L::Set(2.0f) * u - L::Set(1.0f)) * L::Set(erf_radius);
    return L::Set(sigma * 1.41421356f) * ErfInv<L>(x);
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_
