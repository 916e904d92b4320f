// A pixel reconstruction filter sampled by importance: offsets from a pixel's centre
// distributed as the filter, one axis at a time (the filters are separable), by inverting their
// distribution functions over lanes. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_
#undef WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_
#else
#define WAVETRACE_SAMPLING_PIXEL_FILTER_INL_H_
#endif

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

// The inverse error function for |x| < 1, by M. Giles' single-precision approximation
// ("Approximating the erfinv function", GPU Computing Gems Jade, 2011): two polynomials in
// w = -log(1 - x^2), relative error below 4e-7 (absolute 3.7e-7 near 0).
template <class L>
HWY_INLINE typename L::F ErfInv(typename L::F x) {
    using F = typename L::F;
    const F w = L::Neg(Log<L>((L::Set(1.0f) - x) * (L::Set(1.0f) + x)));
    const F c = w - L::Set(2.5f);
    F p = L::Set(2.81022636e-08f);
    for (const float k : {3.43273939e-07f, -3.5233877e-06f, -4.39150654e-06f, 0.00021858087f,
                          -0.00125372503f, -0.00417768164f, 0.246640727f, 1.50140941f})
        p = p * c + L::Set(k);
    const F t = L::Sqrt(w) - L::Set(3.0f);
    F q = L::Set(-0.000200214257f);
    for (const float k : {0.000100950558f, 0.00134934322f, -0.00367342844f, 0.00573950773f,
                          -0.0076224613f, 0.00943887047f, 1.00167406f, 2.83297682f})
        q = q * t + L::Set(k);
    return L::Select(w < L::Set(5.0f), p, q) * x;
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
