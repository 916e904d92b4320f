#include "lights/light_selection.h"

#include <array>
#include <cmath>

#include "util/check.h"

namespace wavetrace {

LightSelection::LightSelection(std::span<const float> power, std::vector<LightBounds> bounds)
    : power_(power) {
    WT_CHECK_EQ(power.size(), bounds.size());
    if (bounds.size() > 1 && bounds.size() <= kLocalLights) bounds_ = std::move(bounds);
}

float LightSelection::importances(Point3 p, Normal3 n, float* w) const {
    float sum = 0.0f;
    for (size_t i = 0; i < bounds_.size(); ++i) {
        w[i] = light_importance(bounds_[i], p, n);
        sum += w[i];
    }
    return sum;
}

// Where no light's importance is positive and finite (a point behind every one-sided light,
// in the dark: no light sends it anything), by power.
LightChoice LightSelection::select_local(float u, Point3 p, Normal3 n) const {
    std::array<float, kLocalLights> w;
    const float sum = importances(p, n, w.data());
    if (!(sum > 0.0f) || !std::isfinite(sum)) return select_by_power(u);
    const float target = u * sum;
    float below = 0.0f;
    size_t last = 0;  // the last light of positive importance
    for (size_t i = 0; i < bounds_.size(); ++i) {
        if (!(w[i] > 0.0f)) continue;
        last = i;
        below += w[i];
        if (target < below) return {i, w[i] / sum};
    }
    return {last, w[last] / sum};  // u * sum rounded up to the sum
}

float LightSelection::probability(size_t i, Point3 p, Normal3 n) const {
    if (!local()) return power_.probability(i);
    std::array<float, kLocalLights> w;
    const float sum = importances(p, n, w.data());
    if (!(sum > 0.0f) || !std::isfinite(sum)) return power_.probability(i);
    return w[i] / sum;
}

}  // namespace wavetrace
