#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "lights/light_selection.cpp"
#include "lights/light_selection.h"

#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "lights/group_choice-inl.h"
#include "lights/light_importance-inl.h"
#include "util/check.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

void LightImportances(const LightBoundsColumns* c, bool cones, Point3 p, Normal3 n, float* w) {
    using D = hn::CappedTag<float, LightSelection::kLanesAtMost>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const size_t N = hn::Lanes(d);
    const auto surface = n.x != 0.0f || n.y != 0.0f || n.z != 0.0f ? L::All() : L::Not(L::All());
    const V3<F> pl{hn::Set(d, p.x), hn::Set(d, p.y), hn::Set(d, p.z)};
    const V3<F> nl{hn::Set(d, n.x), hn::Set(d, n.y), hn::Set(d, n.z)};
    for (size_t k = 0; k + N <= c->size(); k += N) {
        const LightBoundsLanes<L> b = LightBoundsFrom<L>(
            *c, [&](const std::vector<float>& x) { return hn::LoadU(d, x.data() + k); });
        hn::StoreU(LightImportance<L>(b, pl, nl, surface, cones), d, w + k);
    }
}

// The importances of `groups` groups at `count` vertices (rows of p and n, padded to whole
// vectors), a vector of vertices at a time, into w[g * kRowsAtOnce + r], and the choice of a
// group by u[r] (ChooseGroup) into the rows of `choice`.
void GroupChoicesOfRows(const LightBoundsColumns* c,
                        size_t groups,
                        bool cones,
                        const float (*p)[LightSelection::kRowsAtOnce],
                        const float (*n)[LightSelection::kRowsAtOnce],
                        const float* u,
                        size_t count,
                        float* w,
                        LightSelection::GroupChoiceRows* choice) {
    using D = hn::CappedTag<float, LightSelection::kLanesAtMost>;
    using L = FloatLanes<D>;
    using F = hn::Vec<D>;
    const D d;
    const hn::RebindToSigned<D> di;
    const size_t N = hn::Lanes(d);
    const F zero = hn::Zero(d);
    constexpr size_t K = LightSelection::kRowsAtOnce;
    for (size_t r = 0; r < count; r += N) {
        const V3<F> pl{hn::Load(d, p[0] + r), hn::Load(d, p[1] + r), hn::Load(d, p[2] + r)};
        const V3<F> nl{hn::Load(d, n[0] + r), hn::Load(d, n[1] + r), hn::Load(d, n[2] + r)};
        const auto surface =
            hn::Or(hn::Or(hn::Ne(nl.x, zero), hn::Ne(nl.y, zero)), hn::Ne(nl.z, zero));
        for (size_t g = 0; g < groups; ++g) {
            const LightBoundsLanes<L> b = LightBoundsFrom<L>(
                *c, [&](const std::vector<float>& x) { return hn::Set(d, x[g]); });
            hn::Store(LightImportance<L>(b, pl, nl, surface, cones), d, w + g * K + r);
        }
        const GroupChoiceLanes<L> g = ChooseGroup<L>(
            groups, [&](size_t k) { return hn::Load(d, w + k * K + r); }, hn::Load(d, u + r));
        hn::Store(g.sum, d, choice->sum + r);
        hn::Store(g.below, d, choice->below + r);
        hn::Store(g.group, di, choice->group + r);
        hn::Store(g.last, di, choice->last + r);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(LightImportances);
HWY_EXPORT(GroupChoicesOfRows);

LightSelection::LightSelection(std::span<const float> power,
                               std::span<const LightBounds> bounds,
                               std::span<const uint32_t> group_key)
    : power_(power) {
    WT_CHECK_EQ(power.size(), bounds.size());
    WT_CHECK_EQ(power.size(), group_key.size());
    std::unordered_map<uint32_t, uint32_t> group_of_key;
    std::vector<uint32_t> group;
    uint32_t groups = 0;
    for (uint32_t key : group_key) {
        if (key == kOwnGroup) {
            group.push_back(groups++);
            continue;
        }
        const auto [it, added] = group_of_key.try_emplace(key, groups);
        group.push_back(it->second);
        groups += added ? 1 : 0;
    }
    if (groups < 2 || groups > kLocalLights) return;
    group_ = std::move(group);
    lights_of_.resize(groups);
    rank_.resize(group_.size());
    for (uint32_t i = 0; i < group_.size(); ++i) {
        rank_[i] = static_cast<uint32_t>(lights_of_[group_[i]].size());
        lights_of_[group_[i]].push_back(i);
    }
    for (const std::vector<uint32_t>& lights : lights_of_)
        single_.push_back(lights.size() == 1 ? lights[0] : ~0u);
    std::vector<LightBounds> group_bounds;
    for (const std::vector<uint32_t>& lights : lights_of_) {
        std::vector<LightBounds> members;
        std::vector<float> member_power;
        for (uint32_t i : lights) {
            members.push_back(bounds[i]);
            member_power.push_back(power[i]);
        }
        group_bounds.push_back(union_of(members));
        // A group of no power (all its lights black) keeps uniform weights: importance zero.
        bool any = false;
        for (float w : member_power) any = any || w > 0.0f;
        if (!any) std::fill(member_power.begin(), member_power.end(), 1.0f);
        within_.emplace_back(member_power);
    }
    for (const LightBounds& b : group_bounds) cones_ = cones_ || b.cos_theta_o > -1.0f;
    columns_ = light_bounds_columns(group_bounds,
                                    (groups + kLanesAtMost - 1) / kLanesAtMost * kLanesAtMost);
}

float LightSelection::importances(Point3 p, Normal3 n, float* w) const {
    HWY_DYNAMIC_DISPATCH(LightImportances)(&columns_, cones_, p, n, w);
    float sum = 0.0f;
    for (size_t g = 0; g < lights_of_.size(); ++g) sum += w[g];
    return sum;
}

// Where no group's importance is positive and finite (a point behind every one-sided light,
// in the dark: no light sends it anything), by power.
LightChoice LightSelection::select_local(float u, Point3 p, Normal3 n) const {
    alignas(64) std::array<float, kLocalLights> w;
    HWY_DYNAMIC_DISPATCH(LightImportances)(&columns_, cones_, p, n, w.data());
    namespace lanes = HWY_NAMESPACE;
    const lanes::GroupChoiceLanes<lanes::OneLane> c = lanes::ChooseGroup<lanes::OneLane>(
        lights_of_.size(), [&](size_t g) { return w[g]; }, u);
    if (!(c.sum > 0.0f) || !std::isfinite(c.sum)) return select_by_power(u);
    return light_of_group(u, c.sum, c.group, c.last, c.below, w.data(), 1);
}

void LightSelection::select_rows(const float* u,
                                 const float* const p[3],
                                 const float* const n[3],
                                 size_t count,
                                 LightChoice* out) const {
    WT_DCHECK_LE(count, kRowsAtOnce);
    if (!local()) {
        for (size_t r = 0; r < count; ++r) out[r] = select(u[r], {}, {});
        return;
    }
    // The vertices padded to whole vectors (the padding's results are not read).
    alignas(64) float pr[3][kRowsAtOnce] = {}, nr[3][kRowsAtOnce] = {}, ur[kRowsAtOnce] = {};
    for (int a = 0; a < 3; ++a) {
        std::copy(p[a], p[a] + count, pr[a]);
        std::copy(n[a], n[a] + count, nr[a]);
    }
    std::copy(u, u + count, ur);
    alignas(64) std::array<float, kLocalLights * kRowsAtOnce> w;
    GroupChoiceRows c;
    HWY_DYNAMIC_DISPATCH(GroupChoicesOfRows)
    (&columns_, lights_of_.size(), cones_, pr, nr, ur, count, w.data(), &c);
    for (size_t r = 0; r < count; ++r)
        out[r] = !(c.sum[r] > 0.0f) || !std::isfinite(c.sum[r])
                     ? select_by_power(u[r])
                     : light_of_group(u[r], c.sum[r], c.group[r], c.last[r], c.below[r],
                                      w.data() + r, kRowsAtOnce);
}

// The group ChooseGroup chose (group_choice-inl.h; `last` where u * sum rounded up to the sum),
// then the part of u within the group's share chooses its light, by power.
LightChoice LightSelection::light_of_group(float u,
                                           float sum,
                                           int32_t group,
                                           int32_t last,
                                           float below,
                                           const float* w,
                                           size_t stride) const {
    size_t g = static_cast<size_t>(group);
    if (g == lights_of_.size()) {
        g = static_cast<size_t>(last);
        below = sum - w[g * stride];
    }
    const float wg = w[g * stride];
    if (single_[g] != ~0u) return {single_[g], wg / sum, sum};
    const float within_u = std::clamp((u * sum - below) / wg, 0.0f, 0.99999994f);
    float p_within;
    const size_t r = within_[g].sample_discrete(within_u, &p_within);
    return {lights_of_[g][r], wg / sum * p_within, sum};
}

float LightSelection::probability(size_t i, Point3 p, Normal3 n) const {
    if (!local()) return power_.probability(i);
    alignas(64) std::array<float, kLocalLights> w;
    const float sum = importances(p, n, w.data());
    if (!(sum > 0.0f) || !std::isfinite(sum)) return power_.probability(i);
    const uint32_t g = group_[i];
    if (lights_of_[g].size() == 1) return w[g] / sum;
    return w[g] / sum * within_[g].probability(rank_[i]);
}

float LightSelection::probability(size_t i, Point3 p, Normal3 n, float total) const {
    if (!local() || !(total > 0.0f) || !std::isfinite(total)) return probability(i, p, n);
    using L = HWY_NAMESPACE::OneLane;
    const uint32_t g = group_[i];
    const HWY_NAMESPACE::LightBoundsLanes<L> b = HWY_NAMESPACE::LightBoundsFrom<L>(
        columns_, [&](const std::vector<float>& x) { return x[g]; });
    const bool surface = n.x != 0.0f || n.y != 0.0f || n.z != 0.0f;  // OneLane's mask
    const float w =
        HWY_NAMESPACE::LightImportance<L>(b, {p.x, p.y, p.z}, {n.x, n.y, n.z}, surface, cones_);
    if (lights_of_[g].size() == 1) return w / total;
    return w / total * within_[g].probability(rank_[i]);
}

}  // namespace wavetrace
#endif  // HWY_ONCE
