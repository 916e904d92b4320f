#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lights/light_selection.cpp"
#include "lights/light_selection.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <array>
#include <cmath>

#include "lights/light_importance-inl.h"
#include "util/check.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

void LightImportances(const LightBoundsColumns* c, Point3 p, Normal3 n, float* w) {
    using D = hn::CappedTag<float, LightSelection::kLanesAtMost>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const size_t N = hn::Lanes(d);
    const bool surface = n.x != 0.0f || n.y != 0.0f || n.z != 0.0f;
    const V3<F> pl{hn::Set(d, p.x), hn::Set(d, p.y), hn::Set(d, p.z)};
    const V3<F> nl{hn::Set(d, n.x), hn::Set(d, n.y), hn::Set(d, n.z)};
    auto load3 = [&](const std::vector<float>(&xyz)[3], size_t k) {
        return V3<F>{hn::LoadU(d, xyz[0].data() + k), hn::LoadU(d, xyz[1].data() + k),
                     hn::LoadU(d, xyz[2].data() + k)};
    };
    auto load = [&](const std::vector<float>& x, size_t k) { return hn::LoadU(d, x.data() + k); };
    for (size_t k = 0; k + N <= c->size(); k += N) {
        const LightBoundsLanes<L> b{load3(c->centre, k),   load3(c->axis, k), load(c->radius2, k),
                                    load(c->cos_o, k),     load(c->sin_o, k), load(c->cos_e, k),
                                    load(c->two_sided, k), load(c->phi, k),   load(c->kind, k)};
        hn::StoreU(LightImportance<L>(b, pl, nl, surface), d, w + k);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(LightImportances);

LightSelection::LightSelection(std::span<const float> power, std::vector<LightBounds> bounds)
    : power_(power) {
    WT_CHECK_EQ(power.size(), bounds.size());
    if (bounds.size() > 1 && bounds.size() <= kLocalLights)
        columns_ = light_bounds_columns(
            bounds, (bounds.size() + kLanesAtMost - 1) / kLanesAtMost * kLanesAtMost);
}

float LightSelection::importances(Point3 p, Normal3 n, float* w) const {
    HWY_DYNAMIC_DISPATCH(LightImportances)(&columns_, p, n, w);
    float sum = 0.0f;
    for (size_t i = 0; i < size(); ++i) sum += w[i];
    return sum;
}

// Where no light's importance is positive and finite (a point behind every one-sided light,
// in the dark: no light sends it anything), by power.
LightChoice LightSelection::select_local(float u, Point3 p, Normal3 n) const {
    alignas(64) std::array<float, kLocalLights> w;
    const float sum = importances(p, n, w.data());
    if (!(sum > 0.0f) || !std::isfinite(sum)) return select_by_power(u);
    const float target = u * sum;
    float below = 0.0f;
    size_t last = 0;  // the last light of positive importance
    for (size_t i = 0; i < size(); ++i) {
        if (!(w[i] > 0.0f)) continue;
        last = i;
        below += w[i];
        if (target < below) return {i, w[i] / sum};
    }
    return {last, w[last] / sum};  // u * sum rounded up to the sum
}

float LightSelection::probability(size_t i, Point3 p, Normal3 n) const {
    if (!local()) return power_.probability(i);
    alignas(64) std::array<float, kLocalLights> w;
    const float sum = importances(p, n, w.data());
    if (!(sum > 0.0f) || !std::isfinite(sum)) return power_.probability(i);
    return w[i] / sum;
}

}  // namespace wavetrace
#endif  // HWY_ONCE
