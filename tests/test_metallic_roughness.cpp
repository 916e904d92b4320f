// glTF's metallic-roughness material against the specification's own formulas (Appendix B, the
// transmission and clearcoat extensions, the coat about a normal of its own), and its limits: a
// smooth white metal is a mirror, an index-matched thin wall at normal incidence lets everything
// through, the model is reciprocal without a clearcoat. Its sampling is tested with every BSDF's
// in test_bsdf.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bsdfs/bsdf.h"
#include "bsdfs/metallic_roughness.h"
#include "sampling/sampler.h"
#include "sampling/warp.h"

using namespace wavetrace;

namespace {

float u(uint32_t seed, uint32_t i, uint32_t dim) {
    return sample_1d(seed, i, 0, dim);
}

BsdfParams gltf(Color base, float metallic, float roughness, float ior = 1.5f,
                float transmission = 0.0f, float clearcoat = 0.0f,
                float clearcoat_roughness = 0.0f) {
    BsdfParams b;
    b.kind = MaterialKind::MetallicRoughness;
    b.albedo = base;
    b.metallic = metallic;
    b.alpha = b.alpha_v = roughness * roughness;
    b.eta = ior;
    b.transmission = transmission;
    b.clearcoat = clearcoat;
    b.clearcoat_alpha = clearcoat_roughness * clearcoat_roughness;
    return b;
}

// The specification's terms, written as it writes them (double precision): Schlick's Fresnel,
// the GGX D and the visibility V = G / (4 |N.L| |N.V|) of the separable Smith G.
double schlick(double f0, double cos_theta) {
    return f0 + (1 - f0) * std::pow(1 - std::fabs(cos_theta), 5);
}
double d_ggx(double alpha, double n_h) {
    const double a2 = alpha * alpha, t = n_h * n_h * (a2 - 1) + 1;
    return n_h > 0 ? a2 / (M_PI * t * t) : 0;
}
double v_ggx(double alpha, double n_l, double n_v) {
    const double a2 = alpha * alpha;
    n_l = std::fabs(n_l);
    n_v = std::fabs(n_v);
    return 1 / ((n_l + std::sqrt(a2 + (1 - a2) * n_l * n_l)) *
                (n_v + std::sqrt(a2 + (1 - a2) * n_v * n_v)));
}

// f |cos_i| for V = wo, L = wi above the surface or (thin-walled transmission) below it. The
// coat lies about its normal N_c (KHR_materials_clearcoat's clearcoatNormal); where V or L is
// behind N_c it reflects nothing (wavetrace's rule where the extension takes |N_c.V|).
Color spec_eval(const BsdfParams& b, Vec3 wo, Vec3 wi) {
    const double f0 = std::pow((b.eta - 1.0) / (b.eta + 1.0), 2);
    const bool transmitted = wi.z < 0;
    const Vec3 l = transmitted ? Vec3{wi.x, wi.y, -wi.z} : wi;  // V - 2 (N.L) N + L
    const Vec3 h = normalize(wo + l);
    const double v_h = dot(wo, h);
    const double specular = d_ggx(b.alpha, h.z) * v_ggx(b.alpha, l.z, wo.z);
    const double fd = schlick(f0, v_h);
    double out[3];
    for (int c = 0; c < 3; ++c) {
        const double base = b.albedo[c];
        const double fm = schlick(base, v_h);
        double dielectric, metal;
        if (!transmitted) {
            dielectric = fd * specular + (1 - fd) * (1 - b.transmission) * base / M_PI;
            metal = fm * specular;
        } else {
            dielectric = (1 - fd) * b.transmission * base * specular;
            metal = 0;
        }
        double material = (1 - b.metallic) * dielectric + b.metallic * metal;
        const Vec3 nc = b.coat_normal_or_z();
        const double v_c = dot(wo, nc), l_c = dot(l, nc);
        if (b.clearcoat > 0 && v_c > 0) {
            const double fc = 0.04 + 0.96 * std::pow(1 - std::fabs(v_c), 5);
            const double coat = transmitted || l_c <= 0 ? 0
                                                        : d_ggx(b.clearcoat_alpha, dot(h, nc)) *
                                                              v_ggx(b.clearcoat_alpha, l_c, v_c);
            material = (1 - b.clearcoat * fc) * material + b.clearcoat * fc * coat;
        }
        out[c] = material * std::fabs(double(wi.z));
    }
    return {float(out[0]), float(out[1]), float(out[2])};
}

BsdfParams with_coat_normal(BsdfParams b, Vec3 n) {
    b.coat_normal = normalize(n);
    return b;
}

std::vector<BsdfParams> materials() {
    const Color base(0.9f, 0.5f, 0.2f);
    return {gltf(base, 0.0f, 0.5f),
            gltf(base, 1.0f, 0.3f),
            gltf(base, 0.4f, 0.8f, 1.33f),
            gltf(base, 0.0f, 0.4f, 1.5f, 0.7f),
            gltf(base, 0.3f, 0.6f, 2.0f, 1.0f, 0.8f, 0.25f),
            gltf(Color(0.0f), 0.0f, 0.2f, 1.5f, 0.0f, 1.0f, 0.5f),
            with_coat_normal(gltf(base, 0.3f, 0.6f, 2.0f, 1.0f, 0.8f, 0.25f), {0.3f, -0.2f, 0.9f}),
            with_coat_normal(gltf(Color(0.0f), 0.0f, 0.2f, 1.5f, 0.0f, 1.0f, 0.5f),
                             {-0.8f, 0.1f, 0.6f})};
}

std::vector<Vec3> directions() {
    return {normalize(Vec3{0.1f, 0.2f, 0.95f}),   normalize(Vec3{0.6f, -0.2f, 0.5f}),
            normalize(Vec3{-0.9f, 0.1f, 0.15f}),  normalize(Vec3{0.3f, 0.7f, 0.4f}),
            normalize(Vec3{-0.2f, -0.5f, -0.8f}), normalize(Vec3{0.7f, 0.0f, -0.3f})};
}

}  // namespace

TEST(MetallicRoughness, EvaluatesTheSpecificationsFormulas) {
    for (const BsdfParams& b : materials())
        for (Vec3 wo : directions()) {
            if (wo.z < 0) continue;
            for (Vec3 wi : directions()) {
                const Color want = spec_eval(b, wo, wi), got = bsdf_eval(b, wo, wi);
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(got[c], want[c], 2e-5f + 2e-5f * want[c])
                        << "metallic " << b.metallic << " alpha " << b.alpha << " wo.z " << wo.z
                        << " wi.z " << wi.z << " channel " << c;
            }
        }
}

// Seen from behind, the surface is its front mirrored through the tangent plane, with the
// coat's normal negated (-N_c is the back's): mirrored, that is N_c's tangential part negated.
TEST(MetallicRoughness, IsTheSameFromBothSides) {
    for (const BsdfParams& b : materials())
        for (Vec3 wo : directions())
            for (Vec3 wi : directions()) {
                const Vec3 wo_b{wo.x, wo.y, -wo.z}, wi_b{wi.x, wi.y, -wi.z};
                BsdfParams back = b;
                back.coat_normal = {-b.coat_normal.x, -b.coat_normal.y, b.coat_normal.z};
                EXPECT_EQ(bsdf_eval(b, wo, wi), bsdf_eval(back, wo_b, wi_b));
                EXPECT_EQ(bsdf_pdf(b, wo, wi), bsdf_pdf(back, wo_b, wi_b));
            }
    BsdfParams one_sided = materials()[0];
    one_sided.one_sided = true;
    const Vec3 wo = normalize(Vec3{0.2f, 0.1f, -0.9f}), wi = normalize(Vec3{-0.3f, 0.2f, -0.8f});
    EXPECT_GT(max_component(bsdf_eval(materials()[0], wo, wi)), 0.0f);
    EXPECT_EQ(bsdf_eval(one_sided, wo, wi), Color(0.0f));
    EXPECT_FALSE(bsdf_sample(one_sided, wo, 0.5f, 0.5f, 0.5f).valid);
}

// f(wo, wi) = f(wi, wo): f |cos_i| / |cos_i| against f |cos_o| / |cos_o|; the clearcoat's
// Fresnel at the view direction alone breaks it (by the specification), so without one.
TEST(MetallicRoughness, IsReciprocalWithoutAClearcoat) {
    for (const BsdfParams& b : materials()) {
        if (b.clearcoat > 0) continue;
        for (Vec3 wo : directions())
            for (Vec3 wi : directions()) {
                const Color a = bsdf_eval(b, wo, wi) / std::fabs(wi.z);
                const Color r = bsdf_eval(b, wi, wo) / std::fabs(wo.z);
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], r[c], 1e-5f + 1e-5f * a[c]);
            }
    }
}

// A smooth white metal (Fm = 1) is a perfect mirror; a nearly smooth one reflects all but the
// light its masking loses, within 1e-3 at roughness 0.1.
TEST(MetallicRoughness, WhiteMetalIsAMirror) {
    const BsdfParams smooth = gltf(Color(1.0f), 1.0f, 0.0f);
    EXPECT_TRUE(smooth.is_delta());
    for (Vec3 wo : directions()) {
        const BsdfSample s = bsdf_sample(smooth, wo, 0.3f, 0.4f, 0.5f);
        ASSERT_TRUE(s.valid && s.delta);
        EXPECT_EQ(s.wi, Vec3(-wo.x, -wo.y, wo.z));
        EXPECT_EQ(s.weight, Color(1.0f));
    }
    const BsdfParams rough = gltf(Color(1.0f), 1.0f, 0.1f);
    EXPECT_FALSE(rough.is_delta());
    const uint32_t n = 100'000;
    double sum = 0;
    const Vec3 wo = normalize(Vec3{0.4f, 0.1f, 0.9f});
    for (uint32_t i = 0; i < n; ++i) {
        const BsdfSample s = bsdf_sample(rough, wo, u(5, i, 0), u(5, i, 1), u(5, i, 2));
        if (s.valid) sum += s.weight.x;
    }
    EXPECT_NEAR(sum / n, 1.0, 1e-3);
}

// Index-matched (ior 1: F0 = 0), fully transmissive, white and smooth, a thin wall seen head on
// passes all light straight through: the samples' mean weight is 1 (the specular lobe's 2%
// share of the samples carries Fd = 0), and every transmitted sample goes on unchanged.
TEST(MetallicRoughness, IndexMatchedThinWallPassesLightHeadOn) {
    const BsdfParams wall = gltf(Color(1.0f), 0.0f, 0.0f, 1.0f, 1.0f);
    const Vec3 wo{0, 0, 1};
    const uint32_t n = 100'000;
    double sum = 0, sum2 = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const BsdfSample s = bsdf_sample(wall, wo, u(6, i, 0), u(6, i, 1), u(6, i, 2));
        ASSERT_TRUE(s.valid);
        if (s.transmitted) {
            EXPECT_EQ(s.wi, -wo);
        }
        sum += s.weight.x;
        sum2 += double(s.weight.x) * s.weight.x;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1.0, 4 * se + 1e-6);
}

// The directional albedo (the mean sample weight) of a white metal stays below 1 for every
// roughness, also under a clearcoat (the coat's Fresnel mixes two lobes that each lose energy).
// The dielectric part does not: fresnel_mix weighs the diffuse lobe by 1 - F(V.h) for each pair
// of directions rather than by what the specular lobe takes from the view direction, so a white
// dielectric of roughness 0.05 seen at grazing (N.V = 0.08) reflects 1.20 of the light, by the
// specification's formulas (which EvaluatesTheSpecificationsFormulas holds us to).
TEST(MetallicRoughness, WhiteMetalCreatesNoEnergy) {
    const uint32_t n = 200'000;
    for (float roughness : {0.05f, 0.3f, 0.7f, 1.0f})
        for (float clearcoat : {0.0f, 1.0f})
            for (Vec3 wo : {normalize(Vec3{0.1f, 0.0f, 1.0f}), normalize(Vec3{0.9f, 0.0f, 0.3f}),
                            normalize(Vec3{0.99f, 0.0f, 0.08f})}) {
                const BsdfParams b =
                    gltf(Color(1.0f), 1.0f, roughness, 1.5f, 0.0f, clearcoat, roughness);
                double sum = 0, sum2 = 0;
                for (uint32_t i = 0; i < n; ++i) {
                    const BsdfSample s =
                        bsdf_sample(b, wo, u(8, i, 0), u(8, i, 1), u(8, i, 2));
                    const double w = s.valid ? s.weight.x : 0.0;
                    sum += w;
                    sum2 += w * w;
                }
                const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
                EXPECT_LT(mean, 1.0 + 4 * se) << roughness << " " << clearcoat << " " << wo.z;
            }
}

// A smooth coat about a normal of its own reflects about that normal, with the weight of its
// share, k Fc / p_coat: the mean over many samples of the coat-only material (a black base,
// whose specular lobe is smooth too) is k Fc along the coat's mirror direction plus the base's
// Fd (1 - k Fc) along the shading normal's.
TEST(MetallicRoughness, SmoothCoatReflectsAboutItsOwnNormal) {
    BsdfParams b = with_coat_normal(gltf(Color(0.0f), 0.0f, 0.0f, 1.5f, 0.0f, 1.0f, 0.0f),
                                    {0.2f, 0.1f, 0.95f});
    const Vec3 wo = normalize(Vec3{0.3f, -0.4f, 0.8f}), nc = b.coat_normal;
    const Vec3 coat_mirror = 2.0f * dot(wo, nc) * nc - wo, base_mirror{-wo.x, -wo.y, wo.z};
    const float fc = 0.04f + 0.96f * std::pow(1.0f - dot(wo, nc), 5.0f);
    const float fd = 0.04f + 0.96f * std::pow(1.0f - wo.z, 5.0f);
    const uint32_t n = 20'000;
    double coat = 0, coat2 = 0, base = 0, base2 = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const BsdfSample s = bsdf_sample(b, wo, u(9, i, 0), u(9, i, 1), u(9, i, 2));
        ASSERT_TRUE(s.valid && s.delta);
        const double w = s.weight.x;
        if (length(s.wi - coat_mirror) < 1e-5f) {
            coat += w;
            coat2 += w * w;
        } else {
            EXPECT_LT(length(s.wi - base_mirror), 1e-6f);
            base += w;
            base2 += w * w;
        }
    }
    auto se = [&](double sum, double sum2) {
        return std::sqrt((sum2 / n - (sum / n) * (sum / n)) / n);
    };
    EXPECT_NEAR(coat / n, fc, 4 * se(coat, coat2) + 1e-6);
    EXPECT_NEAR(base / n, fd * (1 - fc), 4 * se(base, base2) + 1e-6);
    // From behind, mirrored as the rest.
    const BsdfSample back = bsdf_sample(b, {wo.x, wo.y, -wo.z}, 0.0f, 0.5f, 0.5f);
    ASSERT_TRUE(back.valid);
    const Vec3 nc_back{-nc.x, -nc.y, -nc.z}, wo_back{wo.x, wo.y, -wo.z};
    EXPECT_LT(length(back.wi - (2.0f * dot(wo_back, nc_back) * nc_back - wo_back)), 1e-5f);
}
