// The samplers' designed properties (sampling/sampler-inl.h): the Sobol sampler's pairs of
// dimensions are (0, m, 2)-nets for every power-of-two count of a pixel's samples, its pairs
// and pixels are decorrelated, ZSobol's squares of pixels are nets together, and every value
// is a pure function of its coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "chi2.h"
#include "sampling/sampler.h"
#include "shading/path_vertex.h"

using namespace wavetrace;

namespace {

const Sampler kSobol{7, SamplerKind::Sobol};

// The dimension pairs a path draws as 2D points: the camera's and those of bounces 0 and 5.
std::vector<uint32_t> first_dims_of_pairs() {
    std::vector<uint32_t> dims = {kDimPixelX, kDimLensU};
    for (int bounce : {0, 5})
        for (uint32_t d = 0; d < kBounceDims; d += 2) dims.push_back(bounce_dim(bounce, BounceDim(d)));
    return dims;
}

// Whether 2^m points of dimensions (dim, dim + 1) — samples (pixel, i) — put exactly one in
// every elementary interval [a / 2^k, (a + 1) / 2^k) x [b / 2^(m-k), ...).
bool points_are_net(const Sampler& s,
                    const std::vector<std::pair<uint32_t, uint32_t>>& samples,
                    uint32_t dim,
                    int m) {
    if (samples.size() != (size_t(1) << m)) return false;
    for (int k = 0; k <= m; ++k) {
        std::vector<int> count(samples.size(), 0);
        for (auto [pixel, i] : samples) {
            const auto a = static_cast<uint32_t>(sample_1d(s, pixel, i, dim) * float(1u << k));
            const auto b =
                static_cast<uint32_t>(sample_1d(s, pixel, i, dim + 1) * float(1u << (m - k)));
            ++count[(a << (m - k)) | b];
        }
        for (int c : count)
            if (c != 1) return false;
    }
    return true;
}

// Whether samples [first, first + 2^m) of `pixel` are such a net.
bool is_net(const Sampler& s, uint32_t pixel, uint32_t dim, uint32_t first, int m) {
    std::vector<std::pair<uint32_t, uint32_t>> samples;
    for (uint32_t i = first; i < first + (1u << m); ++i) samples.push_back({pixel, i});
    return points_are_net(s, samples, dim, m);
}

}  // namespace

TEST(Samplers, NamesRoundTrip) {
    for (SamplerKind s : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol})
        EXPECT_EQ(parse_sampler(to_string(s)), s);
    EXPECT_FALSE(parse_sampler("halton").has_value());
}

// Every pair, in several pixels and seeds, for 1 to 2^10 samples from the first one, and for
// the later blocks [j 2^m, (j + 1) 2^m) a render split by sample ranges would start at.
TEST(Samplers, SobolPairsAreNetsForEveryPowerOfTwo) {
    for (uint64_t seed : {0ull, 7ull, 123456789ull})
        for (uint32_t pixel : {0u, 1u, 4095u, 2000003u})
            for (uint32_t dim : first_dims_of_pairs()) {
                const Sampler s{seed, SamplerKind::Sobol};
                for (int m = 0; m <= 10; ++m)
                    ASSERT_TRUE(is_net(s, pixel, dim, 0, m))
                        << "seed " << seed << " pixel " << pixel << " dim " << dim << " m " << m;
                for (uint32_t first : {16u, 48u, 1024u})
                    ASSERT_TRUE(is_net(s, pixel, dim, first, 4)) << "first " << first;
            }
}

namespace {

// Whether samples [0, 2^m) of every pixel of the side x side square at (x0, y0), together,
// put exactly one point in every elementary interval of dimensions (dim, dim + 1).
bool square_is_net(const Sampler& s, int x0, int y0, int side, uint32_t dim, int m) {
    std::vector<std::pair<uint32_t, uint32_t>> samples;
    for (int y = y0; y < y0 + side; ++y)
        for (int x = x0; x < x0 + side; ++x)
            for (uint32_t i = 0; i < (1u << m); ++i)
                samples.push_back({static_cast<uint32_t>(y * s.width + x), i});
    return points_are_net(s, samples, dim, m + 2 * (side == 1 ? 0 : side == 2 ? 1 : 2));
}

}  // namespace

// ZSobol: a pixel's samples are a net for its block of the sequence and for each power of four
// (times 2 where the block's log2 is odd) below it, in the next block too, and so are those of each
// aligned 2 x 2 and 4 x 4 square of pixels together: the sequence's consecutive blocks go to
// neighbouring pixels, what spreads their errors as blue noise. For even and odd log2 of the
// samples per pixel, on an image that is not square.
TEST(Samplers, ZSobolPixelsAndSquaresOfPixelsAreNets) {
    for (int spp : {16, 8})
        for (uint64_t seed : {0ull, 99ull}) {
            const Sampler s = zsobol_sampler(seed, 40, 24, spp);
            const int m = spp == 16 ? 4 : 3;
            ASSERT_EQ(s.log2_spp, m);
            for (uint32_t dim : first_dims_of_pairs()) {
                for (auto [x, y] : {std::pair{0, 0}, {17, 3}, {39, 23}}) {
                    const uint32_t pixel = static_cast<uint32_t>(y * 40 + x);
                    // Whole base-4 digits of the block (a digit's permutation need not keep
                    // its first two values in one half, as pbrt-v4's does not).
                    for (int k = m % 2; k <= m; k += 2)
                        ASSERT_TRUE(is_net(s, pixel, dim, 0, k)) << "spp " << spp << " k " << k;
                    ASSERT_TRUE(is_net(s, pixel, dim, 1u << m, m)) << "the second block";
                }
                for (auto [x, y] : {std::pair{0, 0}, {6, 2}, {36, 20}})
                    ASSERT_TRUE(square_is_net(s, x, y, 2, dim, m))
                        << "spp " << spp << " dim " << dim << " at " << x << "," << y;
                ASSERT_TRUE(square_is_net(s, 4, 8, 4, dim, m)) << "spp " << spp << " dim " << dim;
                // An unaligned pair of neighbours is no part of one block: not a net.
                ASSERT_FALSE(square_is_net(s, 1, 1, 2, dim, m) &&
                             square_is_net(s, 3, 5, 2, dim, m) && square_is_net(s, 5, 7, 2, dim, m))
                    << "dim " << dim;
            }
        }
}

// Padding: dimensions of different pairs are independent, not stratified together (without
// the per-pair shuffle, dimension 2k and 2k + 2 would be the same sequence), and so are the
// same dimension in different pixels. chi^2 of 16 x 16 cells over 4096 points.
TEST(Samplers, SobolPairsAndPixelsAreDecorrelated) {
    auto chi2_of = [](auto u, auto v) {
        std::vector<double> observed(256, 0.0);
        for (uint32_t i = 0; i < 4096; ++i)
            observed[static_cast<int>(u(i) * 16) * 16 + static_cast<int>(v(i) * 16)] += 1;
        double statistic = 0;
        for (double o : observed) statistic += (o - 16) * (o - 16) / 16;
        return chi2::gamma_q(255 / 2.0, statistic / 2);
    };
    for (uint32_t dim : {bounce_dim(0, kDimLightU), bounce_dim(2, kDimBsdfU)}) {
        const double p = chi2_of([&](uint32_t i) { return sample_1d(kSobol, 9, i, kDimPixelX); },
                                 [&](uint32_t i) { return sample_1d(kSobol, 9, i, dim); });
        EXPECT_GT(p, 1e-3) << "pixel x against dimension " << dim;
    }
    // The same for ZSobol, whose pairs differ by their shuffle of the Morton index.
    const Sampler z = zsobol_sampler(7, 64, 64, 4096);
    for (uint32_t dim : {bounce_dim(0, kDimLightU), bounce_dim(2, kDimBsdfU)}) {
        const double pz = chi2_of([&](uint32_t i) { return sample_1d(z, 9, i, kDimPixelX); },
                                  [&](uint32_t i) { return sample_1d(z, 9, i, dim); });
        EXPECT_GT(pz, 1e-3) << "zsobol: pixel x against dimension " << dim;
    }
    // Sample 0 of 4096 pixels, dimension 0 against 1 (a net within a pixel, random across).
    const double p = chi2_of([&](uint32_t i) { return sample_1d(kSobol, i, 0, kDimPixelX); },
                             [&](uint32_t i) { return sample_1d(kSobol, i, 0, kDimPixelY); });
    EXPECT_GT(p, 1e-3) << "first samples of neighbouring pixels";
}

// Each number depends on its coordinates alone, lies in [0, 1), and a seed changes them all.
TEST(Samplers, ValuesArePureFunctionsInTheUnitInterval) {
    for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol}) {
        const Sampler a{3, kind, 13, 5, 7}, b{4, kind, 13, 5, 7};
        int same = 0;
        for (uint32_t i = 0; i < 2000; ++i) {
            const float u = sample_1d(a, i % 13, i, i % 40);
            EXPECT_GE(u, 0.0f);
            EXPECT_LT(u, 1.0f);
            EXPECT_EQ(u, sample_1d(a, i % 13, i, i % 40));
            same += u == sample_1d(b, i % 13, i, i % 40);
        }
        EXPECT_LT(same, 5) << to_string(kind);
    }
    // ZSobol without its layout (a Sampler built by hand) still draws numbers in [0, 1).
    const float u = sample_1d(Sampler{3, SamplerKind::ZSobol}, 17, 5, 2);
    EXPECT_TRUE(u >= 0.0f && u < 1.0f);
}

// The engines draw a vertex's dimensions by pairs (SampleDimPair): the same values as one at a
// time (SampleDim, sample_1d), field by field; the strategies that read no one-sample pair get
// 0 there and the same values elsewhere.
TEST(Samplers, PairsDrawnTogetherEqualEachDimensionAlone) {
    for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol})
        for (bool one_sample : {true, false}) {
            const Sampler s{11, kind, 64, 48, 5};
            for (uint32_t i = 0; i < 300; ++i) {
                const uint32_t pixel = i * 7717, sample = i % 37;
                const int bounce = static_cast<int>(i % 9);
                const VertexSamples v = vertex_samples(s, pixel, sample, bounce, one_sample);
                auto u = [&](BounceDim d) {
                    if (!one_sample && one_sample_pair(d / 2)) return 0.0f;
                    return sample_1d(s, pixel, sample, bounce_dim(bounce, d));
                };
                const VertexSamples alone = vertex_samples_of(u);
                ASSERT_EQ(std::memcmp(&v, &alone, sizeof v), 0)
                    << to_string(kind) << " " << one_sample << " " << i;
            }
        }
}
