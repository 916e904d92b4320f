// Piecewise-constant 1-D and 2-D distributions, sampled by inverting their CDFs (pbrt-v4
// §A.4-A.5): used to pick lights by power and environment-map texels by luminance.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace wavetrace {

class Distribution1D {
  public:
    Distribution1D() = default;
    // Weights must be >= 0 and not all zero.
    explicit Distribution1D(std::span<const float> weights);

    size_t size() const { return pdf_.size(); }
    float total() const { return total_; }
    // Probability of choosing entry i (discrete).
    float probability(size_t i) const { return pdf_[i] / static_cast<float>(pdf_.size()); }
    // Discrete choice; *prob receives its probability and *remapped a fresh uniform number
    // made from the rest of u. Inline: both engines choose a light with it at every vertex.
    size_t sample_discrete(float u, float* prob, float* remapped = nullptr) const {
        const size_t i = find(u);
        const double width = cdf_[i + 1] - cdf_[i];
        if (prob) *prob = probability(i);
        if (remapped)
            *remapped =
                width > 0 ? std::min(0.99999994f, static_cast<float>((u - cdf_[i]) / width)) : 0.0f;
        return i;
    }
    // Continuous sample in [0, 1); *pdf is the density on [0, 1).
    float sample_continuous(float u, float* pdf, size_t* index = nullptr) const;
    float pdf_continuous(float x) const;

  private:
    // The last i with cdf_[i] <= u, skipping zero-width entries: one less than the number of
    // entries <= u. A short table (a scene's few lights) counts them without a branch, where a
    // binary search's branches go either way at random; a long one searches.
    size_t find(float u) const {
        const double x = static_cast<double>(u);
        size_t count = 0;
        if (cdf_.size() <= 16) {
            for (const double c : cdf_) count += c <= x;
        } else {
            count =
                static_cast<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), x) - cdf_.begin());
        }
        return std::min(count == 0 ? 0 : count - 1, pdf_.size() - 1);
    }
    std::vector<float> pdf_;   // density on [0, 1) per entry: n w_i / sum w
    std::vector<double> cdf_;  // n + 1 entries, cdf_[0] = 0, cdf_[n] = 1
    float total_ = 0;
};

// The tables of a Distribution2D as sampling/distribution-inl.h reads them: cumulative sums of
// the weights, the marginal's over rows (nv + 1 entries from 0) and each row's over its nu
// entries (nv rows of nu + 1, each from 0), unnormalized; and a guide table for each run of sums
// (the cutpoint method, Chen & Asau 1974): for g cells of [0, 1), g a power of two, and j in
// [0, g], the entry the search finds for the target (j / g) total, computed in float as the
// search computes its targets. A u in cell j = floor(u g) then finds its entry between guide[j]
// and guide[j + 1]: the binary search runs over a few entries instead of all of them.
struct Distribution2DTables {
    int nu = 0, nv = 0;
    const float* marginal = nullptr;
    const float* conditional = nullptr;
    int gu = 0, gv = 0;                          // the cells of a row's guide and of the marginal's
    const int32_t* marginal_guide = nullptr;     // gv + 1 entries
    const int32_t* conditional_guide = nullptr;  // nv rows of gu + 1
};

// Density over [0,1)^2 proportional to a grid of positive weights (row-major, rows = v),
// sampled by inverting its CDFs (pbrt-v4 §A.5) in the lane formulas of
// sampling/distribution-inl.h. The sums are floats, as the lanes search them; each is at least
// the float after the one before, so every entry keeps a positive width, and the density is
// that of the widths, which the search samples exactly.
class Distribution2D {
  public:
    Distribution2D() = default;
    Distribution2D(std::span<const float> weights, int nu, int nv);
    bool empty() const { return marginal_.empty(); }
    Distribution2DTables tables() const {
        return {nu_, nv_, marginal_.data(),       conditional_.data(),
                gu_, gv_, marginal_guide_.data(), conditional_guide_.data()};
    }

  private:
    int nu_ = 0, nv_ = 0, gu_ = 0, gv_ = 0;
    std::vector<float> marginal_, conditional_;
    std::vector<int32_t> marginal_guide_, conditional_guide_;
};

}  // namespace wavetrace
