// Multiple importance sampling weights over lanes (shading/mis.h has the scalar
// function, the one-lane instance). Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_SHADING_MIS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SHADING_MIS_INL_H_
#undef WAVETRACE_SHADING_MIS_INL_H_
#else
#define WAVETRACE_SHADING_MIS_INL_H_
#endif

#include "math/lanes-inl.h"
#include "shading/mis.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Balance: p_a / (p_a + p_b). Power (beta = 2): 1 / (1 + (p_b / p_a)^2), divided through by
// p_a so that the squares cannot overflow. Guarded, in this order of precedence: an infinite
// p_a takes all the weight (1), an infinite p_b or a p_a that is not positive none (0), a p_b
// that is not positive all (1); never NaN.
template <class L>
HWY_INLINE typename L::F MisWeight(MisHeuristic h, typename L::F pdf_a, typename L::F pdf_b) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    F w;
    if (h == MisHeuristic::Balance) {
        w = pdf_a / (pdf_a + pdf_b);
    } else {
        const F r = pdf_b / pdf_a;
        w = one / (one + r * r);
    }
    w = L::Select(pdf_b > zero, w, one);
    w = L::Select(L::Or(L::IsInf(pdf_b), L::Not(pdf_a > zero)), zero, w);
    return L::Select(L::IsInf(pdf_a), one, w);
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SHADING_MIS_INL_H_
