// Every BSDF's sampling routine against its density (chi-square, 1e5+ samples, significance
// 1e-3), and every density's integral over the sphere against the probability of a sample.
#include <gtest/gtest.h>

#include <cmath>

#include "chi2.h"
#include "sampling/sampler.h"
#include "sampling/warp.h"
#include "shading/bsdf.h"

using namespace wavetrace;

namespace {

constexpr uint32_t kSamples = 400'000;
constexpr double kSignificance = 1e-3;

float u(uint32_t seed, uint32_t i, uint32_t dim) {
    return sample_1d(seed, i, 0, dim);
}

struct Case {
    const char* name;
    BsdfParams b;
    Vec3 wo;
};

std::vector<Case> smooth_cases() {
    auto params = [](MaterialKind k, float alpha) {
        BsdfParams b;
        b.kind = k;
        b.albedo = Color(0.8f, 0.6f, 0.4f);
        b.alpha = alpha;
        return b;
    };
    Vec3 oblique = normalize(Vec3{0.6f, -0.2f, 0.5f});
    Vec3 grazing = normalize(Vec3{0.95f, 0.1f, 0.12f});
    Vec3 below = normalize(Vec3{-0.3f, 0.4f, -0.7f});  // two-sided shading
    return {
        {"lambertian", params(MaterialKind::Lambertian, 0), oblique},
        {"lambertian-below", params(MaterialKind::Lambertian, 0), below},
        // Roughness 0.2, 0.5 and 1.0 (alpha = roughness^2).
        {"metal-0.2", params(MaterialKind::Metal, 0.04f), oblique},
        {"metal-0.5", params(MaterialKind::Metal, 0.25f), oblique},
        {"metal-1.0", params(MaterialKind::Metal, 1.0f), oblique},
        {"metal-0.5-grazing", params(MaterialKind::Metal, 0.25f), grazing},
        {"metal-0.5-below", params(MaterialKind::Metal, 0.25f), below},
        {"isotropic", params(MaterialKind::Isotropic, 0), oblique},
    };
}

}  // namespace

TEST(Bsdf, SamplingMatchesDensityChiSquare) {
    uint32_t seed = 100;
    for (const Case& c : smooth_cases()) {
        ++seed;
        auto result = chi2::test(
            [&](uint32_t i) -> std::optional<Vec3> {
                BsdfSample s = bsdf_sample(c.b, c.wo, u(seed, i, 0), u(seed, i, 1), u(seed, i, 2));
                if (!s.valid) return std::nullopt;
                return s.wi;
            },
            [&](Vec3 wi) { return double(bsdf_pdf(c.b, c.wo, wi)); }, kSamples);
        std::printf("chi2 %-18s %s\n", c.name, result.summary().c_str());
        EXPECT_GT(result.p_value, kSignificance) << c.name << ": " << result.summary();
    }
}

TEST(Bsdf, SampleWeightIsEvalOverPdf) {
    for (const Case& c : smooth_cases())
        for (uint32_t i = 0; i < 2000; ++i) {
            BsdfSample s = bsdf_sample(c.b, c.wo, u(7, i, 0), u(7, i, 1), u(7, i, 2));
            if (!s.valid) continue;
            EXPECT_NEAR(s.pdf, bsdf_pdf(c.b, c.wo, s.wi), 1e-4f * s.pdf) << c.name;
            Color expect = bsdf_eval(c.b, c.wo, s.wi) / s.pdf;
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(s.weight[k], expect[k], 1e-4f * std::max(1.0f, expect[k])) << c.name;
        }
}

// The density integrates to the probability that sampling returns a direction at all: 1, or
// less for rough metal whose reflected microfacet samples can land below the horizon. Both
// sides are Monte Carlo estimates; the bound is 4 standard errors of the integral estimate
// plus 4 of the binomial fraction.
TEST(Bsdf, DensityIntegratesToTheSamplingProbability) {
    for (const Case& c : smooth_cases()) {
        const uint32_t n = 400'000;
        double sum = 0, sum2 = 0;
        for (uint32_t i = 0; i < n; ++i) {
            Vec3 w = sample_uniform_sphere(u(9, i, 0), u(9, i, 1));
            double v = bsdf_pdf(c.b, c.wo, w) / uniform_sphere_pdf();
            sum += v;
            sum2 += v * v;
        }
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        size_t valid = 0;
        for (uint32_t i = 0; i < n; ++i)
            valid += bsdf_sample(c.b, c.wo, u(10, i, 0), u(10, i, 1), u(10, i, 2)).valid;
        double p = double(valid) / n, se_p = std::sqrt(p * (1 - p) / n);
        std::printf("integral %-18s %.5f +- %.5f, sampling probability %.5f\n", c.name, mean, se,
                    p);
        EXPECT_NEAR(mean, p, 4 * se + 4 * se_p + 1e-9) << c.name;
        if (c.b.kind != MaterialKind::Metal) {
            EXPECT_EQ(valid, n) << c.name;
        }
    }
}

// A smooth dielectric has two delta lobes: reflection with probability F and refraction
// otherwise. Chi-square over the two outcomes, and Snell's law for the refracted direction.
TEST(Bsdf, DielectricChoosesLobesByFresnel) {
    BsdfParams glass;
    glass.kind = MaterialKind::Dielectric;
    glass.eta = 1.5f;
    for (Vec3 wo : {normalize(Vec3{0.3f, 0.1f, 0.9f}), normalize(Vec3{0.8f, 0.0f, 0.2f}),
                    normalize(Vec3{0.2f, 0.1f, -0.9f}), normalize(Vec3{0.7f, 0.0f, -0.5f})}) {
        float eta = wo.z > 0 ? 1.5f : 1 / 1.5f;
        float f = fresnel_dielectric(std::fabs(wo.z), eta);
        const uint32_t n = 200'000;
        uint32_t reflected = 0;
        for (uint32_t i = 0; i < n; ++i) {
            BsdfSample s = bsdf_sample(glass, wo, u(11, i, 0), u(11, i, 1), u(11, i, 2));
            ASSERT_TRUE(s.valid && s.delta);
            if (!s.transmitted) {
                ++reflected;
                EXPECT_EQ(s.wi, Vec3(-wo.x, -wo.y, wo.z));
                continue;
            }
            // Snell: eta_i sin_i = eta_t sin_t, on the other side, in the plane of incidence.
            float sin_i = std::sqrt(1 - wo.z * wo.z), sin_t = std::sqrt(1 - s.wi.z * s.wi.z);
            EXPECT_NEAR(sin_i, eta * sin_t, 1e-5f);
            EXPECT_LT(wo.z * s.wi.z, 0.0f);
            EXPECT_NEAR(s.weight.x, 1 / (eta * eta), 1e-6f);
        }
        if (f >= 1.0f) {
            EXPECT_EQ(reflected, n);  // total internal reflection
            continue;
        }
        double e_r = f * n, e_t = (1 - f) * n;
        double stat = (reflected - e_r) * (reflected - e_r) / e_r +
                      (n - reflected - e_t) * (n - reflected - e_t) / e_t;
        double p = chi2::gamma_q(0.5, stat / 2);
        std::printf("dielectric wo.z %+.3f: F %.4f, reflected %.4f, p %.3f\n", wo.z, f,
                    double(reflected) / n, p);
        EXPECT_GT(p, kSignificance);
    }
}

TEST(Bsdf, FresnelLimits) {
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-6f);  // ((1.5 - 1) / 2.5)^2
    EXPECT_NEAR(fresnel_dielectric(1e-6f, 1.5f), 1.0f, 1e-4f);  // grazing
    EXPECT_EQ(fresnel_dielectric(0.3f, 1 / 1.5f), 1.0f);        // beyond the critical angle
}

TEST(Bsdf, ChiSquareDetectsAWrongDensity) {
    // The test itself must be able to fail: cosine samples judged against a uniform density.
    auto result = chi2::test(
        [&](uint32_t i) -> std::optional<Vec3> {
            return sample_cosine_hemisphere(u(3, i, 0), u(3, i, 1));
        },
        [&](Vec3 w) { return w.z > 0 ? 0.5 / 3.14159265358979 : 0.0; }, 100'000);
    EXPECT_LT(result.p_value, 1e-6) << result.summary();
}
