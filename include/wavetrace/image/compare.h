// Comparing a render with a reference image: image-mean difference, relative MSE, and
// per-block z-tests when the variances of the two images are known (the test Mitsuba 3 runs on
// its renders against references: Jakob et al., mitsuba3 src/render/tests/test_render.py).
#pragma once

#include <optional>

#include "wavetrace/image/image.h"

namespace wavetrace {

struct CompareOptions {
    int block = 8;        // z-tests on the means of block x block pixel squares
    double alpha = 0.01;  // probability that a correct render fails the z-tests (all blocks)
    // Without variances no z-test is possible: the images pass if both bounds hold.
    double max_mean_rel_diff = 1e-2;
    double max_rel_mse = 1e-2;
};

// One block and channel's z-test: z = (m_ours - m_ref) / sqrt(var(m_ours) + var(m_ref)). The
// whole image is tested the same way, as one more block.
struct BlockTest {
    int x = -1, y = -1;  // the block's top-left pixel
    int channel = -1;
    double z = 0.0;
    double p = 1.0;  // two-sided p-value, erfc(|z| / sqrt 2)
};

struct ImageComparison {
    double mean_ours = 0.0, mean_ref = 0.0;  // over all pixels and channels
    double mean_rel_diff = 0.0;              // |mean_ours - mean_ref| / mean_ref
    double rel_mse = 0.0;                    // mean of (o - r)^2 / (r^2 + 1e-3) over values
    bool z_tested = false;                   // a variance image was given
    int tests = 0;                           // (blocks + the whole image) x channels
    double image_z[3] = {0, 0, 0};           // the whole image's z per channel
    double level = 0.0;  // Sidak-corrected per-test level: 1 - (1 - alpha)^(1 / tests)
    int failed = 0;      // tests with p below the level
    BlockTest worst;     // the smallest p
    bool pass = false;
    // Per pixel, the |z| of its block per channel (z-tested comparisons only): for a z-map.
    Image block_z;
};

// Compares `ours` with `ref`. Variances are of each pixel's mean (what `render --variance`
// writes); a missing one counts as zero (e.g. a converged reference). Throws
// std::invalid_argument if sizes differ, a variance is negative or not finite, or the block is
// not positive. Non-finite pixel values fail the test they fall in.
ImageComparison compare_images(const Image& ours,
                               const Image& ref,
                               const Image* ours_variance,
                               const Image* ref_variance,
                               const CompareOptions& options = {});

}  // namespace wavetrace
