// Comparing renders with references: the statistics of `compare_images` on images with known
// noise, and the CLI's `render --variance` and `compare` together.
#include <gtest/gtest.h>

#include <random>

#include "cli_run.h"
#include "wavetrace/image/compare.h"
#include "wavetrace/image/image.h"

using namespace wavetrace;

namespace {

// A smooth reference and a render of it with Gaussian noise of the given per-pixel variance.
struct Noisy {
    Image ref, ours, variance;
};
Noisy noisy(int w, int h, float sigma, uint32_t seed) {
    Noisy n{Image(w, h), Image(w, h), Image(w, h)};
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, sigma);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const Color c(0.2f + 0.6f * x / w, 0.5f, 0.3f + 0.4f * y / h);
            n.ref.at(x, y) = c;
            n.ours.at(x, y) = c + Color(gauss(rng), gauss(rng), gauss(rng));
            n.variance.at(x, y) = Color(sigma * sigma);
        }
    return n;
}

}  // namespace

// A correct render fails with probability alpha (the z-tests are Sidak-corrected over all
// blocks): over 200 independent noisy images at alpha = 0.01 about 2 fail; more than 8 would
// happen with probability below 1e-4 if the test were right.
TEST(CompareImages, CorrectRendersFailAtTheStatedRate) {
    int failed = 0;
    for (uint32_t seed = 0; seed < 200; ++seed) {
        Noisy n = noisy(16, 16, 0.05f, seed);
        CompareOptions o;
        o.block = 4;
        ImageComparison c = compare_images(n.ours, n.ref, &n.variance, nullptr, o);
        EXPECT_TRUE(c.z_tested);
        EXPECT_EQ(c.tests, 3 * 4 * 4);
        failed += !c.pass;
    }
    EXPECT_LE(failed, 8);
}

// A bias of 8 standard deviations of one block's mean, in one block and channel: found, and
// named as the worst block.
TEST(CompareImages, FindsABiasedBlock) {
    Noisy n = noisy(16, 16, 0.05f, 1);
    const float block_sigma = 0.05f / 4;  // 16 pixels per 4x4 block
    for (int y = 8; y < 12; ++y)
        for (int x = 4; x < 8; ++x) n.ours.at(x, y).y += 8 * block_sigma;
    CompareOptions o;
    o.block = 4;
    ImageComparison c = compare_images(n.ours, n.ref, &n.variance, nullptr, o);
    EXPECT_FALSE(c.pass);
    EXPECT_EQ(c.failed, 1);
    EXPECT_EQ(c.worst.x, 4);
    EXPECT_EQ(c.worst.y, 8);
    EXPECT_EQ(c.worst.channel, 1);
    EXPECT_GT(c.worst.z, 6.0);
    // Splitting the variance between the two images gives the same test.
    Image half = n.variance;
    for (Color& v : half.pixels) v = 0.5f * v;
    ImageComparison split = compare_images(n.ours, n.ref, &half, &half, o);
    EXPECT_NEAR(split.worst.z, c.worst.z, 1e-4 * c.worst.z);
}

TEST(CompareImages, WithoutVariancesUsesTheMeanAndMseBounds) {
    Noisy n = noisy(8, 8, 0.0f, 0);
    ImageComparison same = compare_images(n.ref, n.ref, nullptr, nullptr);
    EXPECT_TRUE(same.pass);
    EXPECT_FALSE(same.z_tested);
    EXPECT_EQ(same.rel_mse, 0.0);
    Image brighter = n.ref;
    for (Color& c : brighter.pixels) c = 1.05f * c;
    ImageComparison b = compare_images(brighter, n.ref, nullptr, nullptr);
    EXPECT_NEAR(b.mean_rel_diff, 0.05, 1e-5);
    EXPECT_FALSE(b.pass);
}

TEST(CompareImages, RefusesMismatchedInputs) {
    Noisy n = noisy(8, 8, 0.1f, 0);
    EXPECT_THROW(compare_images(n.ours, Image(8, 7), nullptr, nullptr), std::invalid_argument);
    EXPECT_THROW(compare_images(n.ours, n.ref, &n.ref, &(n.variance = Image(4, 4))),
                 std::invalid_argument);
    Image negative(8, 8);
    negative.at(3, 3).x = -1.0f;
    EXPECT_THROW(compare_images(n.ours, n.ref, &negative, nullptr), std::invalid_argument);
}

// Two renders of one scene with different seeds are two samples of the same image: with
// their variances, compare passes; against a render missing the indirect light it fails. (64
// spp: with fewer, a pixel's sample variance underestimates its heavy-tailed distribution.)
TEST(Cli, CompareTellsNoiseFromADifferentImage) {
    TempDir dir;
    auto path = [&](const char* name) { return "'" + (dir.path() / name).string() + "'"; };
    const std::string common =
        "render " + scene_path("cornell").string() + " --width 32 --height 32 --spp 64";
    ASSERT_EQ(run_cli(dir, common + " --seed 1 -o " + path("a.exr") + " --variance " +
                               path("a-var.exr"))
                  .code,
              0);
    ASSERT_EQ(run_cli(dir, common + " --seed 2 -o " + path("b.exr") + " --variance " +
                               path("b-var.exr"))
                  .code,
              0);
    ASSERT_EQ(run_cli(dir, common + " --seed 3 --max-depth 2 -o " + path("direct.exr") +
                               " --variance " + path("direct-var.exr"))
                  .code,
              0);
    CliResult same = run_cli(dir, "compare " + path("a.exr") + " " + path("b.exr") +
                                      " --ours-var " + path("a-var.exr") + " --ref-var " +
                                      path("b-var.exr"));
    EXPECT_EQ(same.code, 0) << same.out << same.err;
    EXPECT_NE(same.out.find("result    pass"), std::string::npos) << same.out;
    EXPECT_NE(same.out.find("z-tests   48 (8x8 blocks x 3 channels)"), std::string::npos)
        << same.out;
    CliResult differs = run_cli(dir, "compare " + path("direct.exr") + " " + path("b.exr") +
                                         " --ours-var " + path("direct-var.exr") +
                                         " --ref-var " + path("b-var.exr"));
    EXPECT_EQ(differs.code, 1) << differs.out << differs.err;
    EXPECT_NE(differs.out.find("result    differs"), std::string::npos) << differs.out;
}

TEST(Cli, CompareAndVarianceRefuseBadInput) {
    TempDir dir;
    auto path = [&](const char* name) { return "'" + (dir.path() / name).string() + "'"; };
    CliResult missing = run_cli(dir, "compare " + path("nope.exr") + " " + path("nope2.exr"));
    EXPECT_EQ(missing.code, 2);
    EXPECT_NE(missing.err.find("nope.exr"), std::string::npos) << missing.err;
    const std::string render = "render " + scene_path("cornell").string() +
                               " --width 8 --height 8 --spp 1 -o " + path("x.exr");
    CliResult ldr = run_cli(dir, render + " --variance " + path("v.png"));
    EXPECT_EQ(ldr.code, 2);
    EXPECT_NE(ldr.err.find("linear float"), std::string::npos) << ldr.err;
    CliResult aov = run_cli(dir, render + " --aov albedo --variance " + path("v.exr"));
    EXPECT_EQ(aov.code, 2);
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.exr"));
    ASSERT_EQ(run_cli(dir, render).code, 0);
    CliResult block = run_cli(dir, "compare " + path("x.exr") + " " + path("x.exr") + " --block 0");
    EXPECT_EQ(block.code, 2);
    CliResult self = run_cli(dir, "compare " + path("x.exr") + " " + path("x.exr"));
    EXPECT_EQ(self.code, 0) << self.out;
}
