// Plastic (bsdfs/plastic.h) beyond what every BSDF is tested for in test_bsdf.cpp: the coating's
// table against a Monte Carlo estimate of the same albedo, energy with a white base, the
// smooth limit of the rough coating, reciprocity, and the nonlinear rule.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "bsdfs/bsdf.h"
#include "bsdfs/fresnel.h"
#include "bsdfs/plastic.h"
#include "microfacets/microfacet.h"
#include "sampling/sampler.h"

using namespace wavetrace;

namespace {

float u(uint32_t seed, uint32_t i, uint32_t dim) {
    return sample_1d(seed, i, 0, dim);
}

BsdfParams plastic(const CoatingTable* table, Microfacet d, float alpha, float eta, Color base) {
    BsdfParams b;
    b.kind = MaterialKind::Plastic;
    b.albedo = base;
    b.eta = eta;
    b.distribution = d;
    b.alpha = b.alpha_v = alpha;
    b.specular_weight = 1.0f / (1.0f + mean(base));
    b.coating = table;
    return b;
}

Vec3 at_cos(float mu) {
    return {std::sqrt(1.0f - mu * mu), 0.0f, mu};
}

// The mean weight of n samples from wo (the directional albedo) and its standard error.
struct Estimate {
    double mean = 0, se = 0;
};
Estimate albedo(const BsdfParams& b, Vec3 wo, uint32_t seed, uint32_t n = 400'000) {
    double sum = 0, sum2 = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const BsdfSample s = bsdf_sample(b, wo, u(seed, i, 0), u(seed, i, 1), u(seed, i, 2));
        const double w = s.valid ? s.weight.x : 0.0;
        sum += w;
        sum2 += w * w;
    }
    const double m = sum / n;
    return {m, std::sqrt(std::max(0.0, sum2 / n - m * m) / n)};
}

}  // namespace

// The table's transmittance against a Monte Carlo estimate of its definition (Mitsuba 3's
// eval_transmittance): random visible normals m of o, the mean of (1 - F(o.m)) G1(t), t the
// refraction of o at m; and with a black base the specular albedo estimated by sampling the
// BSDF is at most 1 - T(mu): light refracted in and then masked is lost, not reflected.
TEST(Plastic, CoatingTableIsTheTransmittance) {
    for (Microfacet d : {Microfacet::Beckmann, Microfacet::Ggx})
        for (float alpha : {0.05f, 0.3f, 0.8f}) {
            const float eta = 1.5f;
            const CoatingTable t = rough_coating_table(d, alpha, eta);
            const MicrofacetDistribution md{d, alpha, alpha};
            const BsdfParams b = plastic(&t, d, alpha, eta, Color(0.0f));
            for (float mu : {0.05f, 0.3f, 0.7f, 1.0f}) {
                const Vec3 o = at_cos(mu);
                const uint32_t n = 400'000;
                double sum = 0, sum2 = 0;
                for (uint32_t i = 0; i < n; ++i) {
                    const Vec3 m =
                        md.sample_visible(o, sample_1d(43, i, 0, 0), sample_1d(43, i, 0, 1));
                    const float c = dot(o, m);
                    const Vec3 tr =
                        -o / eta + (c / eta - std::sqrt(1 - (1 - c * c) / (eta * eta))) * m;
                    const double v =
                        c > 0 && tr.z < 0 ? (1 - fresnel_dielectric(c, eta)) * md.g1(tr) : 0.0;
                    sum += v;
                    sum2 += v * v;
                }
                const double mean = sum / n,
                             se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
                const float table = t.transmittance_at(mu);
                const Estimate e = albedo(b, o, 41);
                std::printf(
                    "coating %s alpha %.2f mu %.2f: T sampled %.5f +- %.5f, table %.5f; "
                    "specular albedo %.5f\n",
                    d == Microfacet::Ggx ? "ggx" : "beckmann", alpha, mu, mean, se, table, e.mean);
                // The table interpolates between nodes 1/63 apart: up to 1e-3 of curvature.
                EXPECT_NEAR(mean, table, 4 * se + 1e-3) << alpha << " " << mu;
                EXPECT_LE(e.mean - 4 * e.se - 1e-3, 1.0 - table) << alpha << " " << mu;
            }
        }
}

// As alpha -> 0 the rough coating becomes the smooth one: T(mu) -> 1 - F(mu), and the internal
// reflectance -> Mitsuba's sum over the table's nodes of the smooth internal Fresnel term.
TEST(Plastic, RoughCoatingTendsToTheSmoothOne) {
    const float eta = 1.5f;
    const CoatingTable t = rough_coating_table(Microfacet::Ggx, 0.002f, eta);
    double inner = 0;
    for (int k = 0; k < CoatingTable::kSize; ++k) {
        const float mu = std::max(1e-6f, float(k) / (CoatingTable::kSize - 1));
        if (mu > 0.1f) {
            EXPECT_NEAR(t.transmittance[k], 1.0f - fresnel_dielectric(mu, eta), 2e-3);
        }
        inner += mu * fresnel_dielectric(mu, 1.0f / eta);
    }
    EXPECT_NEAR(t.internal_reflectance, 2.0 * inner / CoatingTable::kSize, 2e-3);
    // The smooth coating's fit lies within 0.5% of the exact internal diffuse reflectance,
    // 1 - (1 - Fdr_ext) / eta^2, Fdr_ext = 2 * integral of F(mu) mu.
    for (float e : {1.3f, 1.5f, 1.9f, 2.4f}) {
        double ext = 0;
        const int n = 100'000;
        for (int k = 0; k < n; ++k) {
            const double mu = (k + 0.5) / n;
            ext += 2.0 * mu * fresnel_dielectric(float(mu), e) / n;
        }
        const double exact = 1.0 - (1.0 - ext) / (double(e) * e);
        std::printf("Fdr eta %.1f: fit %.5f, exact %.5f\n", e, plastic_internal_reflectance(e),
                    exact);
        EXPECT_NEAR(plastic_internal_reflectance(e), exact, 5e-3 * exact);
    }
}

// A white base under a smooth coating returns all light (the fit's error aside): what the
// coating reflects, F, plus what it lets through and out again, 1 - F.
TEST(Plastic, WhiteSmoothPlasticReflectsEverything) {
    for (float eta : {1.3f, 1.5f, 1.9f})
        for (float mu : {0.1f, 0.5f, 0.9f}) {
            const BsdfParams b = plastic(nullptr, Microfacet::Ggx, 0.0f, eta, Color(1.0f));
            const Estimate e = albedo(b, at_cos(mu), 43);
            std::printf("white smooth plastic eta %.1f mu %.1f: %.5f +- %.5f\n", eta, mu, e.mean,
                        e.se);
            EXPECT_NEAR(e.mean, 1.0, 4 * e.se + 5e-3);
        }
}

// f(wo, wi) = f(wi, wo): eval, which includes cos theta_i, over cos theta_i.
TEST(Plastic, IsReciprocal) {
    const CoatingTable t = rough_coating_table(Microfacet::Beckmann, 0.2f, 1.6f);
    for (float alpha : {0.0f, 0.2f}) {
        const BsdfParams b =
            plastic(alpha > 0 ? &t : nullptr, Microfacet::Beckmann, alpha, 1.6f, Color(0.5f));
        for (uint32_t i = 0; i < 500; ++i) {
            const Vec3 a =
                normalize(Vec3(u(5, i, 0) - 0.5f, u(5, i, 1) - 0.5f, u(5, i, 2) + 0.05f));
            const Vec3 c =
                normalize(Vec3(u(5, i, 3) - 0.5f, u(5, i, 4) - 0.5f, u(5, i, 5) + 0.05f));
            const float f_ac = bsdf_eval(b, a, c).x / c.z, f_ca = bsdf_eval(b, c, a).x / a.z;
            EXPECT_NEAR(f_ac, f_ca, 1e-4f * std::max(1.0f, f_ac)) << alpha;
        }
    }
}

// The nonlinear rule R / (1 - R Fdr) equals the linear R / (1 - Fdr) for a white base and is
// darker for any other; from behind a one-sided plastic is black, a two-sided one mirrored.
TEST(Plastic, NonlinearAndSides) {
    const Vec3 wo = normalize(Vec3(0.3f, 0.2f, 0.8f)), wi = normalize(Vec3(-0.4f, 0.1f, 0.7f));
    for (float r : {1.0f, 0.5f}) {
        BsdfParams b = plastic(nullptr, Microfacet::Ggx, 0.0f, 1.5f, Color(r));
        const float linear = bsdf_eval(b, wo, wi).x;
        b.nonlinear = true;
        const float nonlinear = bsdf_eval(b, wo, wi).x;
        const float fdr = plastic_internal_reflectance(1.5f);
        EXPECT_NEAR(nonlinear / linear, (1 - fdr) / (1 - r * fdr), 1e-5f) << r;
    }
    BsdfParams b = plastic(nullptr, Microfacet::Ggx, 0.0f, 1.5f, Color(0.5f));
    const Vec3 wo_below{wo.x, wo.y, -wo.z}, wi_below{wi.x, wi.y, -wi.z};
    EXPECT_FLOAT_EQ(bsdf_eval(b, wo_below, wi_below).x, bsdf_eval(b, wo, wi).x);
    b.one_sided = true;
    EXPECT_EQ(bsdf_eval(b, wo_below, wi_below).x, 0.0f);
    EXPECT_FALSE(bsdf_sample(b, wo_below, 0.9f, 0.3f, 0.4f).valid);
}
