// Which light a vertex samples. In proportion to the lights' power — the same choice at every
// point, a table lookup — or, for a scene of at most kLocalLights light groups, a group in
// proportion to its importance at the vertex (light_bounds.h), then a light of the group by
// power: a light far away, facing away or outside its cone is chosen less, and the lights that
// do light the point share the samples by what each brings. A group is one light, or the
// emissive triangles of one material (a mesh light, whose triangles the group's bounds hold
// together). pbrt-v4's exhaustive light sampler chooses likewise; a BVH over the lights'
// bounds (its default, Conty Estevez and Kulla 2018) would carry the idea to many groups,
// which here keep the power.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lights/light_bounds.h"
#include "sampling/distribution.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

struct LightChoice {
    size_t index = 0;
    float probability = 0.0f;
    float total = 0.0f;  // chosen by importance: the groups' sum at the vertex, else 0
};

class LightSelection {
  public:
    // Local importance pays for its cost per vertex (every group's bounds evaluated) up to this
    // many groups.
    static constexpr size_t kLocalLights = 32;
    // The columns are padded to a multiple of the widest vector's lanes.
    static constexpr size_t kLanesAtMost = 16;
    static_assert(kLocalLights % kLanesAtMost == 0);
    // The most vertices select_rows takes at once.
    static constexpr size_t kRowsAtOnce = 64;
    static_assert(kRowsAtOnce % kLanesAtMost == 0);

    LightSelection() = default;
    // Light i's power, bounds and group key (all of the same size, not empty; power not all
    // zero): the lights of one key other than kOwnGroup form a group, each other light its own.
    static constexpr uint32_t kOwnGroup = ~0u;
    LightSelection(std::span<const float> power,
                   std::span<const LightBounds> bounds,
                   std::span<const uint32_t> group_key);

    size_t size() const { return power_.size(); }
    bool local() const { return columns_.size() > 0; }

    // Picks a light with u for the vertex at p with normal n (zero in a medium). Inline: both
    // engines choose at every vertex.
    LightChoice select(float u, Point3 p, Normal3 n) const {
        if (size() == 1) return {0, power_.probability(0)};
        if (local()) return select_local(u, p, n);
        return select_by_power(u);
    }
    // select() of `count` vertices (at most kRowsAtOnce): u[r], p and n the r-th of their
    // rows (x, y, z). The same choices, bit for bit; the importances are taken with the vertices
    // in lanes, a group at a time, which fills the vectors where there are fewer groups than
    // lanes.
    void select_rows(const float* u,
                     const float* const p[3],
                     const float* const n[3],
                     size_t count,
                     LightChoice* out) const;
    // The group choices of select_rows' vertices (group_choice-inl.h's GroupChoiceLanes).
    struct GroupChoiceRows {
        alignas(64) float sum[kRowsAtOnce], below[kRowsAtOnce];
        alignas(64) int32_t group[kRowsAtOnce], last[kRowsAtOnce];
    };
    // The probability that select(·, p, n) picks light i.
    float probability(size_t i, Point3 p, Normal3 n) const;
    // The same where select() at (p, n) returned `total` (LightChoice::total): one group's
    // importance evaluated rather than all of them (the same number, up to rounding).
    float probability(size_t i, Point3 p, Normal3 n, float total) const;

    // The choice in proportion to power alone, everywhere, and its probabilities.
    LightChoice select_by_power(float u) const {
        LightChoice c;
        c.index = power_.sample_discrete(u, &c.probability);
        return c;
    }
    float power_probability(size_t i) const { return power_.probability(i); }

  private:
    LightChoice select_local(float u, Point3 p, Normal3 n) const;
    LightChoice light_of_group(float u,
                               float sum,
                               int32_t group,
                               int32_t last,
                               float below,
                               const float* w,
                               size_t stride) const;
    // Every group's importance at (p, n) into w (columns_.size() entries, in lanes); the sum
    // over the groups, in order.
    float importances(Point3 p, Normal3 n, float* w) const;

    Distribution1D power_;
    LightBoundsColumns columns_;                    // per group; empty: by power alone
    bool cones_ = false;                            // whether any group emits within a cone
    std::vector<uint32_t> group_;                   // light i's group
    std::vector<uint32_t> rank_;                    // light i's place among its group's lights
    std::vector<std::vector<uint32_t>> lights_of_;  // group g's lights, in order
    std::vector<uint32_t> single_;                  // group g's light if it has one, else ~0
    std::vector<Distribution1D> within_;            // group g: its lights by power
};

}  // namespace wavetrace
