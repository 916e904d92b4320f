// The choice of a light group by one uniform number in proportion to the groups' importances
// at a vertex (light_selection.h), written once over lanes: the megakernel's one vertex with
// OneLane, the wavefront's vertices a vector at a time. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_LIGHTS_GROUP_CHOICE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_LIGHTS_GROUP_CHOICE_INL_H_
#undef WAVETRACE_LIGHTS_GROUP_CHOICE_INL_H_
#else
#define WAVETRACE_LIGHTS_GROUP_CHOICE_INL_H_
#endif

#include <cstddef>
#include <cstdint>

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// sum: the groups' importances summed in group order. group: the group whose share of
// [0, sum) holds u * sum, shares in group order, and below the shares before it; or, where
// u * sum rounded up to the sum, the number of groups, and last is the last group of positive
// importance (the caller takes it).
template <class L>
struct GroupChoiceLanes {
    typename L::F sum, below;
    typename L::I group, last;
};

// w(g): group g's importances in the lanes. Without a branch per group, which a random u
// would make unpredictable.
template <class L, class W>
HWY_INLINE GroupChoiceLanes<L> ChooseGroup(size_t groups, W w, typename L::F u) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    F sum = zero;
    for (size_t g = 0; g < groups; ++g) sum = sum + w(g);
    const F target = u * sum;
    F below = zero, below_chosen = zero;
    auto group = L::SetI(static_cast<int32_t>(groups)), last = L::SetI(0);
    auto found = L::Not(L::All());
    for (size_t g = 0; g < groups; ++g) {
        const F wg = w(g);
        const auto positive = wg > zero;
        const auto take = L::AndNot(found, L::And(positive, target < below + wg));
        found = L::Or(found, take);
        group = L::SelectI(take, L::SetI(static_cast<int32_t>(g)), group);
        below_chosen = L::Select(take, below, below_chosen);
        last = L::SelectI(positive, L::SetI(static_cast<int32_t>(g)), last);
        below = L::Select(positive, below + wg, below);
    }
    return {sum, below_chosen, group, last};
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_LIGHTS_GROUP_CHOICE_INL_H_
