// Which light a vertex samples. In proportion to the lights' power — the same choice at every
// point, a table lookup — or, for a scene of at most kLocalLights lights, in proportion to
// their importance at the vertex (light_bounds.h): a light far away, facing away or outside
// its cone is chosen less, and the lights that do light the point share the samples by what
// each brings. pbrt-v4's exhaustive light sampler chooses likewise; a BVH over the lights'
// bounds (its default, Conty Estevez and Kulla 2018) would carry the idea to many lights,
// which here keep the power.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "lights/light_bounds.h"
#include "sampling/distribution.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

struct LightChoice {
    size_t index = 0;
    float probability = 0.0f;
};

class LightSelection {
  public:
    // Local importance pays for its cost per vertex (every light's bounds evaluated) up to this
    // many lights.
    static constexpr size_t kLocalLights = 32;
    // The columns are padded to a multiple of the widest vector's lanes.
    static constexpr size_t kLanesAtMost = 16;
    static_assert(kLocalLights % kLanesAtMost == 0);

    LightSelection() = default;
    // Light i's power and bounds (both of the same size, not empty; power not all zero).
    LightSelection(std::span<const float> power, std::vector<LightBounds> bounds);

    size_t size() const { return power_.size(); }
    bool local() const { return columns_.size() > 0; }

    // Picks a light with u for the vertex at p with normal n (zero in a medium). Inline: both
    // engines choose at every vertex.
    LightChoice select(float u, Point3 p, Normal3 n) const {
        if (size() == 1) return {0, power_.probability(0)};
        if (local()) return select_local(u, p, n);
        return select_by_power(u);
    }
    // The probability that select(·, p, n) picks light i.
    float probability(size_t i, Point3 p, Normal3 n) const;

    // The choice in proportion to power alone, everywhere, and its probabilities.
    LightChoice select_by_power(float u) const {
        LightChoice c;
        c.index = power_.sample_discrete(u, &c.probability);
        return c;
    }
    float power_probability(size_t i) const { return power_.probability(i); }

  private:
    LightChoice select_local(float u, Point3 p, Normal3 n) const;
    // Every light's importance at (p, n) into w (columns_.size() entries, in lanes); the sum of
    // the first size(), in order.
    float importances(Point3 p, Normal3 n, float* w) const;

    Distribution1D power_;
    LightBoundsColumns columns_;  // empty: by power alone
};

}  // namespace wavetrace
