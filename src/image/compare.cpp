#include "wavetrace/image/compare.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wavetrace {

namespace {

void check_same_size(const Image& a, const Image& b, const char* what) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument(std::string(what) + " is " + std::to_string(b.width) + "x" +
                                    std::to_string(b.height) + ", the image is " +
                                    std::to_string(a.width) + "x" + std::to_string(a.height));
}

void check_variance(const Image& v, const char* what) {
    for (const Color& c : v.pixels)
        for (int k = 0; k < 3; ++k)
            if (!(c[k] >= 0.0f) || !std::isfinite(c[k]))
                throw std::invalid_argument(std::string(what) +
                                            " holds a negative or non-finite value");
}

// Float rounding in what is compared: images hold 32-bit floats (24-bit mantissas), and a
// renderer that sums its samples in float is a few ulps off. Each pixel's difference is given
// a rounding error of standard deviation 2^-20 (16 ulps) of its size (|ours| + |reference|),
// as a variance added to the pixel's own, so that a test without variance (a background seen
// directly) tells rounding from a real difference (1e-4 of the value is 6 SD off in an 8 x 8
// block).
constexpr double kRounding = 0x1p-20;
double rounding_variance(float ours, float ref) {
    const double r = kRounding * (std::fabs(double(ours)) + std::fabs(double(ref)));
    return r * r;
}

// A difference of sums over its standard deviation (the 1/n of means cancels); an exact
// difference without variance is infinitely significant, a non-finite one too.
double z_score(double diff, double sd) {
    if (!std::isfinite(diff)) return INFINITY;
    if (sd > 0) return diff / sd;
    return diff == 0 ? 0.0 : INFINITY;
}

}  // namespace

ImageComparison compare_images(const Image& ours,
                               const Image& ref,
                               const Image* ours_variance,
                               const Image* ref_variance,
                               const CompareOptions& options) {
    check_same_size(ref, ours, "the image compared");
    if (ours_variance) {
        check_same_size(ours, *ours_variance, "the variance of the image");
        check_variance(*ours_variance, "the variance of the image");
    }
    if (ref_variance) {
        check_same_size(ref, *ref_variance, "the variance of the reference");
        check_variance(*ref_variance, "the variance of the reference");
    }
    if (options.block < 1) throw std::invalid_argument("the block size must be positive");
    if (ours.pixels.empty()) throw std::invalid_argument("the images are empty");

    ImageComparison r;
    const double values = 3.0 * double(ours.pixels.size());
    double sum_o = 0, sum_r = 0, sq = 0;
    for (size_t i = 0; i < ours.pixels.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            const double o = ours.pixels[i][k], f = ref.pixels[i][k];
            sum_o += o;
            sum_r += f;
            sq += (o - f) * (o - f) / (f * f + 1e-3);
        }
    r.mean_ours = sum_o / values;
    r.mean_ref = sum_r / values;
    // Equal means differ by nothing, black images included; against a black reference any
    // other mean differs infinitely.
    r.mean_rel_diff = r.mean_ours == r.mean_ref ? 0.0
                      : r.mean_ref == 0         ? INFINITY
                                                : std::fabs(r.mean_ours - r.mean_ref) /
                                                      std::fabs(r.mean_ref);
    r.rel_mse = sq / values;

    r.z_tested = ours_variance || ref_variance;
    if (!r.z_tested) {
        r.pass = std::isfinite(r.rel_mse) && r.mean_rel_diff <= options.max_mean_rel_diff &&
                 r.rel_mse <= options.max_rel_mse;
        return r;
    }
    // Block means and the variances of those means (pixels are independent: the variance of a
    // mean of n pixel means is the sum of their variances over n^2; z is the same computed
    // from sums).
    const int b = options.block;
    const int bx = (ours.width + b - 1) / b, by = (ours.height + b - 1) / b;
    r.tests = 3 * bx * by + 3;
    r.block_z = Image(ours.width, ours.height);
    r.level = 1.0 - std::pow(1.0 - options.alpha, 1.0 / r.tests);
    for (int y0 = 0; y0 < ours.height; y0 += b)
        for (int x0 = 0; x0 < ours.width; x0 += b)
            for (int k = 0; k < 3; ++k) {
                double so = 0, sr = 0, vo = 0, vr = 0;
                int n = 0;
                for (int y = y0; y < std::min(y0 + b, ours.height); ++y)
                    for (int x = x0; x < std::min(x0 + b, ours.width); ++x, ++n) {
                        so += ours.at(x, y)[k];
                        sr += ref.at(x, y)[k];
                        if (ours_variance) vo += ours_variance->at(x, y)[k];
                        if (ref_variance) vr += ref_variance->at(x, y)[k];
                        vr += rounding_variance(ours.at(x, y)[k], ref.at(x, y)[k]);
                    }
                BlockTest t{x0, y0, k};
                t.z = z_score(so - sr, std::sqrt(vo + vr));
                t.p = std::erfc(std::fabs(t.z) / std::sqrt(2.0));
                if (t.p < r.level) ++r.failed;
                if (r.worst.channel < 0 || t.p < r.worst.p) r.worst = t;
                for (int y = y0; y < std::min(y0 + b, ours.height); ++y)
                    for (int x = x0; x < std::min(x0 + b, ours.width); ++x)
                        r.block_z.at(x, y)[k] = static_cast<float>(std::fabs(t.z));
            }
    // The whole image is one more block per channel: a bias spread thinly over every block
    // (a render 1% too bright) hides in each block's noise but not in the image's mean.
    for (int k = 0; k < 3; ++k) {
        double so = 0, sr = 0, vo = 0, vr = 0;
        for (size_t i = 0; i < ours.pixels.size(); ++i) {
            so += ours.pixels[i][k];
            sr += ref.pixels[i][k];
            if (ours_variance) vo += ours_variance->pixels[i][k];
            if (ref_variance) vr += ref_variance->pixels[i][k];
            vr += rounding_variance(ours.pixels[i][k], ref.pixels[i][k]);
        }
        r.image_z[k] = z_score(so - sr, std::sqrt(vo + vr));
        const double p = std::erfc(std::fabs(r.image_z[k]) / std::sqrt(2.0));
        if (p < r.level) ++r.failed;
    }
    r.pass = r.failed == 0;
    return r;
}

}  // namespace wavetrace
