// Pearson's chi-square goodness-of-fit test of a direction sampler against its density, on
// a sphere binned into equal-area cells (cos theta x phi), in the manner of Mitsuba's
// chi2.py: expected counts are the density integrated over each cell, cells expecting fewer
// than 5 samples are pooled, and the p-value comes from the chi-square distribution.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "wavetrace/math/constants.h"
#include "wavetrace/math/vec3.h"

namespace chi2 {

using wavetrace::Vec3;

// Regularized upper incomplete gamma Q(a, x) (Numerical Recipes §6.2: series for x < a + 1,
// continued fraction otherwise), in double.
inline double gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    double gln = std::lgamma(a);
    if (x < a + 1) {
        double sum = 1.0 / a, term = sum, ap = a;
        for (int n = 0; n < 10000; ++n) {
            ap += 1;
            term *= x / ap;
            sum += term;
            if (std::fabs(term) < std::fabs(sum) * 1e-15) break;
        }
        return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
    }
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
    for (int i = 1; i < 10000; ++i) {
        double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::fabs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::fabs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        double del = d * c;
        h *= del;
        if (std::fabs(del - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - gln) * h;
}

struct Result {
    double statistic = 0;
    int dof = 0;
    double p_value = 0;
    int pooled = 0;  // cells pooled for expecting < 5
    size_t samples = 0, lost = 0;
    std::string summary() const {
        return "chi2 " + std::to_string(statistic) + ", dof " + std::to_string(dof) + ", p " +
               std::to_string(p_value) + ", pooled cells " + std::to_string(pooled) +
               ", lost samples " + std::to_string(lost) + "/" + std::to_string(samples);
    }
};

// sample(i) returns a unit direction, or nothing for a lost sample; pdf(w) its density.
inline Result test(const std::function<std::optional<Vec3>(uint32_t)>& sample,
                   const std::function<double(Vec3)>& pdf,
                   uint32_t n,
                   int cos_bins = 24,
                   int phi_bins = 48) {
    const double kPi = 3.14159265358979323846;
    auto cell = [&](Vec3 w) {
        int i = std::clamp(static_cast<int>((w.z + 1.0f) * 0.5f * cos_bins), 0, cos_bins - 1);
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2 * kPi;
        int j = std::clamp(static_cast<int>(phi / (2 * kPi) * phi_bins), 0, phi_bins - 1);
        return i * phi_bins + j;
    };
    Result r;
    r.samples = n;
    std::vector<double> observed(cos_bins * phi_bins, 0.0), expected(cos_bins * phi_bins, 0.0);
    for (uint32_t s = 0; s < n; ++s) {
        auto w = sample(s);
        if (!w) {
            ++r.lost;
            continue;
        }
        observed[cell(*w)] += 1;
    }
    // Expected counts: n times the density integrated over each cell, by the midpoint rule in
    // (cos theta, phi), where the area element is exactly d(cos) d(phi). Cells where the
    // density is not constant, and their neighbours (the edge of a light's solid angle may
    // clip a cell between the coarse grid's points), are integrated on a grid eight times
    // finer, so that discontinuities do not bias the expectation: a boundary across a cell
    // cuts about 64 of its 4,096 points, moving the cell's integral by under 1%, which is a
    // fifth of the Poisson noise of a cell expecting 400 samples.
    const double dz = 2.0 / cos_bins, dphi = 2 * kPi / phi_bins;
    auto integrate = [&](int i, int j, int sub, bool* varies) {
        double sum = 0, lo = INFINITY, hi = -INFINITY;
        for (int a = 0; a < sub; ++a)
            for (int b = 0; b < sub; ++b) {
                double z = -1 + (i + (a + 0.5) / sub) * dz;
                double phi = (j + (b + 0.5) / sub) * dphi;
                double rr = std::sqrt(std::max(0.0, 1 - z * z));
                double p =
                    pdf(Vec3(float(rr * std::cos(phi)), float(rr * std::sin(phi)), float(z)));
                sum += p;
                lo = std::min(lo, p);
                hi = std::max(hi, p);
            }
        if (varies) *varies = hi > lo * 1.05 && (lo == 0 || hi > 0);
        return sum / (sub * sub) * dz * dphi * n;
    };
    std::vector<char> varies(cos_bins * phi_bins, 0);
    for (int i = 0; i < cos_bins; ++i)
        for (int j = 0; j < phi_bins; ++j) {
            bool v = false;
            expected[i * phi_bins + j] = integrate(i, j, 8, &v);
            varies[i * phi_bins + j] = v;
        }
    for (int i = 0; i < cos_bins; ++i)
        for (int j = 0; j < phi_bins; ++j) {
            bool refine = false;
            for (int di = -1; di <= 1; ++di)
                for (int dj = -1; dj <= 1; ++dj) {
                    int ii = i + di, jj = (j + dj + phi_bins) % phi_bins;
                    if (ii >= 0 && ii < cos_bins && varies[ii * phi_bins + jj]) refine = true;
                }
            if (refine) expected[i * phi_bins + j] = integrate(i, j, 64, nullptr);
        }
    // Pool low-expectation cells (Mitsuba: into one cell), then Pearson's statistic.
    std::vector<int> order(expected.size());
    for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double pool_obs = 0, pool_exp = 0;
    int cells = 0;
    for (int k : order) {
        if (expected[k] < 5) {
            pool_obs += observed[k];
            pool_exp += expected[k];
            ++r.pooled;
            continue;
        }
        r.statistic += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
        ++cells;
    }
    if (pool_exp > 0) {
        r.statistic += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
        ++cells;
    } else if (pool_obs > 0) {
        r.statistic = INFINITY;
    }
    r.dof = cells - 1;
    r.p_value = std::isfinite(r.statistic) ? gamma_q(r.dof / 2.0, r.statistic / 2.0) : 0.0;
    return r;
}

}  // namespace chi2
