#include "sampling/distribution.h"

#include <cmath>

#include "wavetrace/math/constants.h"

namespace wavetrace {

Distribution1D::Distribution1D(std::span<const float> weights)
    : pdf_(weights.size()), cdf_(weights.size() + 1, 0.0) {
    double sum = 0;
    for (size_t i = 0; i < weights.size(); ++i) sum += weights[i];
    const bool uniform = !(sum > 0);  // all zero: fall back to a uniform choice
    sum = 0;
    for (size_t i = 0; i < weights.size(); ++i) {
        sum += uniform ? 1.0 : weights[i];
        cdf_[i + 1] = sum;
    }
    total_ = static_cast<float>(sum);
    const double n = static_cast<double>(weights.size());
    for (size_t i = 0; i < weights.size(); ++i) {
        cdf_[i + 1] /= sum;
        pdf_[i] = static_cast<float>((uniform ? 1.0 : weights[i]) / sum * n);
    }
    cdf_.back() = 1.0;
}

float Distribution1D::sample_continuous(float u, float* pdf, size_t* index) const {
    size_t i = find(u);
    double width = cdf_[i + 1] - cdf_[i];
    double du = width > 0 ? (u - cdf_[i]) / width : 0.0;
    if (pdf) *pdf = pdf_[i];
    if (index) *index = i;
    float x = static_cast<float>((static_cast<double>(i) + du) / static_cast<double>(pdf_.size()));
    return std::min(x, 0.99999994f);
}

float Distribution1D::pdf_continuous(float x) const {
    size_t i = std::min(pdf_.size() - 1, static_cast<size_t>(std::max(0.0f, x) * pdf_.size()));
    return pdf_[i];
}

namespace {

// Appends the float running sums 0, w0, w0 + w1, ... of `weights` (summed in double), each at
// least the float after the one before; returns the double total.
double append_sums(std::span<const float> weights, std::vector<float>& out) {
    double sum = 0;
    float previous = 0.0f;
    out.push_back(previous);
    for (const float w : weights) {
        sum += w;
        previous = std::max(static_cast<float>(sum), std::nextafter(previous, kInfinity));
        out.push_back(previous);
    }
    return sum;
}

// The cells of a guide over n entries: the largest power of two at most n / 2 (at least 1), so
// that a cell spans about two entries where the weights are even.
int guide_cells(int n) {
    int g = 1;
    while (2 * g <= n / 2) g *= 2;
    return g;
}

// Appends the guide (Distribution2DTables) of the n + 1 running sums `sums` over g cells:
// guide[j] is the last i in [0, n) with sums[i] <= (j / g) sums[n], that product rounded as
// SampleSums rounds u sums[n].
void append_guide(const float* sums, int n, int g, std::vector<int32_t>& out) {
    const float total = sums[n];
    int i = 0;
    for (int j = 0; j <= g; ++j) {
        const float target = static_cast<float>(j) * (1.0f / static_cast<float>(g)) * total;
        while (i + 1 < n && sums[i + 1] <= target) ++i;
        out.push_back(i);
    }
}

}  // namespace

Distribution2D::Distribution2D(std::span<const float> weights, int nu, int nv)
    : nu_(nu), nv_(nv) {
    conditional_.reserve(static_cast<size_t>(nu + 1) * nv);
    std::vector<float> rows(nv);
    for (int v = 0; v < nv; ++v)
        rows[v] = static_cast<float>(
            append_sums(weights.subspan(static_cast<size_t>(v) * nu, nu), conditional_));
    append_sums(rows, marginal_);
    gu_ = guide_cells(nu);
    gv_ = guide_cells(nv);
    conditional_guide_.reserve(static_cast<size_t>(gu_ + 1) * nv);
    for (int v = 0; v < nv; ++v)
        append_guide(conditional_.data() + static_cast<size_t>(v) * (nu + 1), nu, gu_,
                     conditional_guide_);
    append_guide(marginal_.data(), nv, gv_, marginal_guide_);
}

}  // namespace wavetrace
