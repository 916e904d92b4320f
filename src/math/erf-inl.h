// The complementary and inverse error functions over lanes, for the Gaussian pixel filter and
// the Beckmann microfacet distribution. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_MATH_ERF_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_MATH_ERF_INL_H_
#undef WAVETRACE_MATH_ERF_INL_H_
#else
#define WAVETRACE_MATH_ERF_INL_H_
#endif

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// erfc(a) e^(a^2) for a >= 0, so that erfc(a) = ErfcOverGaussian(a) e^(-a^2) shares its
// exponential with the formula that calls it: Hastings' approximation, Abramowitz & Stegun
// 7.1.26, t (a1 + t (a2 + ... + t a5)) with t = 1 / (1 + p a); erfc's absolute error stays
// below 1.5e-7.
template <class L>
HWY_INLINE typename L::F ErfcOverGaussian(typename L::F a) {
    using F = typename L::F;
    const F t = L::Set(1.0f) / (L::Set(1.0f) + L::Set(0.3275911f) * a);
    F p = L::Set(1.061405429f);
    for (const float c : {-1.453152027f, 1.421413741f, -0.284496736f, 0.254829592f})
        p = p * t + L::Set(c);
    return p * t;
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

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_MATH_ERF_INL_H_
