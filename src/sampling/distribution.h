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
    // made from the rest of u.
    size_t sample_discrete(float u, float* prob, float* remapped = nullptr) const;
    // Continuous sample in [0, 1); *pdf is the density on [0, 1).
    float sample_continuous(float u, float* pdf, size_t* index = nullptr) const;
    float pdf_continuous(float x) const;

  private:
    size_t find(float u) const;
    std::vector<float> pdf_;   // density on [0, 1) per entry: n w_i / sum w
    std::vector<double> cdf_;  // n + 1 entries, cdf_[0] = 0, cdf_[n] = 1
    float total_ = 0;
};

// Density over [0,1)^2 proportional to a grid of weights (row-major, rows = v).
class Distribution2D {
  public:
    Distribution2D() = default;
    Distribution2D(std::span<const float> weights, int nu, int nv);
    // Samples (u, v) in [0,1)^2 and returns its density on the unit square.
    void sample(float u1, float u2, float* u, float* v, float* pdf) const;
    float pdf(float u, float v) const;
    bool empty() const { return rows_.empty(); }

  private:
    std::vector<Distribution1D> rows_;  // conditional p(u | v)
    Distribution1D marginal_;           // p(v)
};

}  // namespace wavetrace
