// Mitsuba 3's principled BSDFs against their formulas where they are simple to write (at normal
// incidence, and the thin sheet's diffuse transmitter), and the loaders' translation of
// Mitsuba's principled and principledthin. Their sampling is tested with every BSDF's in
// test_bsdf.cpp, their images against Mitsuba's references by ctest's reference tests.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "bsdfs/bsdf.h"
#include "bsdfs/principled.h"
#include "temp_dir.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

BsdfParams principled(Color base, float roughness, float metallic) {
    BsdfParams b;
    b.kind = MaterialKind::Principled;
    b.albedo = base;
    b.eta = 1.5f;
    b.metallic = metallic;
    b.principled.roughness = roughness;
    principled_alphas(roughness, 0.0f, &b.alpha, &b.alpha_v);
    return b;
}

const Vec3 kNormal{0.0f, 0.0f, 1.0f};

void expect_color_near(Color got, Color want, float rel, const char* what) {
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(got[c], want[c], rel * want[c]) << what << " channel " << c;
}

}  // namespace

// At normal incidence (o = i = n, h = n) Burley's diffuse is c / pi (Schlick weights 0, no
// retro-reflection), the specular lobe F D / 4 with D = 1 / (pi alpha^2) and G = 1, F the
// dielectric's R0 = 0.04, or for a metal Schlick(c, 1) = c.
TEST(Principled, NormalIncidenceIsDiffusePlusSpecular) {
    const Color c(0.8f, 0.6f, 0.4f);
    const float r = 0.5f, alpha = r * r, d = 1.0f / (float(M_PI) * alpha * alpha);
    expect_color_near(bsdf_eval(principled(c, r, 0.0f), kNormal, kNormal),
                      c / float(M_PI) + Color(0.04f * d / 4.0f), 1e-5f, "dielectric");
    expect_color_near(bsdf_eval(principled(c, r, 1.0f), kNormal, kNormal), c * (d / 4.0f), 1e-5f,
                      "metal");
    // The clearcoat: 0.25 k Schlick(0.04, 1) GTR1(n) at alpha lerp(0.1, 0.001, gloss).
    BsdfParams coat = principled(c, r, 1.0f);
    coat.clearcoat = 0.6f;
    coat.clearcoat_alpha = 0.1f;
    const float a2 = 0.01f;
    const float gtr1 = (a2 - 1.0f) / (float(M_PI) * std::log(a2) * a2);
    expect_color_near(bsdf_eval(coat, kNormal, kNormal),
                      c * (d / 4.0f) + Color(0.25f * 0.6f * 0.04f * gtr1), 1e-5f, "clearcoat");
}

// From behind, a principled surface without transmission has only its dielectric interface,
// weighted by (1 - metallic) spec_trans: nothing.
TEST(Principled, OpaqueFromBehindReflectsNothing) {
    const BsdfParams b = principled(Color(0.5f), 0.4f, 0.2f);
    const Vec3 o = normalize(Vec3{0.3f, 0.1f, -0.9f}), i = normalize(Vec3{-0.2f, 0.3f, -0.8f});
    EXPECT_EQ(bsdf_eval(b, o, i), Color(0.0f));
    EXPECT_EQ(bsdf_eval(b, o, Vec3{-i.x, -i.y, -i.z}), Color(0.0f));
}

// The thin sheet with all of its diffuse light transmitted (Mitsuba's diff_trans 2) and no
// specular lobe is a Lambertian transmitter c / pi, seen alike from both sides, reflecting
// nothing.
TEST(Principled, ThinSheetOfFullDiffuseTransmissionIsLambertian) {
    const Color c(0.7f, 0.1f, 0.1f);
    BsdfParams b = principled(c, 0.5f, 0.0f);
    b.principled.thin = true;
    b.principled.diff_trans = 1.0f;
    for (const Vec3 o : {normalize(Vec3{0.3f, 0.1f, 0.9f}), normalize(Vec3{0.3f, 0.1f, -0.9f})}) {
        const Vec3 i = normalize(Vec3{-0.4f, 0.2f, o.z > 0 ? -0.7f : 0.7f});
        expect_color_near(bsdf_eval(b, o, i), c * (std::fabs(i.z) / float(M_PI)), 1e-6f,
                          "transmitted");
        EXPECT_EQ(bsdf_eval(b, o, Vec3{i.x, i.y, -i.z}), Color(0.0f));
    }
}

TEST(Principled, SpecularAmountGivesTheIndexOfRefraction) {
    EXPECT_NEAR(principled_eta_of_specular(0.5f), 1.5f, 1e-6f);  // R0 = 0.04
    const float eta = principled_eta_of_specular(0.7f), r = (eta - 1) / (eta + 1);
    EXPECT_NEAR(r * r, 0.08f * 0.7f, 1e-6f);
}

// Mitsuba's principled with textured weights becomes our principled material, its textures
// kept; principledthin a thin one with diffuse transmission.
TEST(Principled, MitsubaPrincipledKeepsItsTexturedWeights) {
    const std::filesystem::path dir =
        std::filesystem::path(WAVETRACE_REFERENCE_DIR) / "mitsuba3/tests/scenes/bsdf_spheres";
    const Scene full = load_scene((dir / "test_texturedprincipled1_path.xml").string());
    bool found = false;
    for (const Material& x : full.materials) {
        if (x.kind != MaterialKind::Principled) continue;
        found = true;
        EXPECT_FALSE(x.principled.thin);
        EXPECT_NE(x.principled.metallic.texture, kNone);
        EXPECT_NE(x.principled.anisotropic.texture, kNone);
        EXPECT_NE(x.principled.clearcoat.texture, kNone);
        EXPECT_NE(x.principled.sheen.texture, kNone);
        EXPECT_EQ(x.principled.roughness.texture, kNone);
        EXPECT_FLOAT_EQ(x.principled.roughness.value, 0.15f);
        EXPECT_FLOAT_EQ(x.ior, principled_eta_of_specular(0.7f));
        EXPECT_TRUE(x.anisotropic());
    }
    EXPECT_TRUE(found);
    const Scene thin = load_scene((dir / "test_texturedprincipledthin_path.xml").string());
    found = false;
    for (const Material& x : thin.materials) {
        if (x.kind != MaterialKind::Principled) continue;
        found = true;
        EXPECT_TRUE(x.principled.thin);
        EXPECT_NE(x.principled.diff_trans.texture, kNone);
        EXPECT_FLOAT_EQ(x.ior, 1.33f);
    }
    EXPECT_TRUE(found);
}

// Our JSON's principled: an index or a specular amount, not both; a weight of the other variant
// is refused, naming it and where it is.
TEST(Principled, SceneFileRefusesContradictions) {
    TempDir dir;
    auto load = [&](const std::string& material) {
        const auto path =
            dir.write("p.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"p": )" + material + R"(},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "p"}]})");
        try {
            load_scene(path.string());
            return std::string();
        } catch (const std::exception& e) {
            return std::string(e.what());
        }
    };
    EXPECT_EQ(load(R"({"type": "principled", "sheen": {"type": "uv_checker", "scale": 4,
                      "even": 0.2, "odd": 0.9}, "ior": 1.4})"),
              "");
    const std::string both = load(R"({"type": "principled", "ior": 1.4, "specular": 0.3})");
    EXPECT_NE(both.find("/materials/p/specular"), std::string::npos) << both;
    EXPECT_NE(both.find("not both"), std::string::npos) << both;
    const std::string thin = load(R"({"type": "principled", "diff_trans": 1})");
    EXPECT_NE(thin.find("/materials/p/diff_trans"), std::string::npos) << thin;
    const std::string range = load(R"({"type": "principled", "thin": true, "diff_trans": 2.5})");
    EXPECT_NE(range.find("/materials/p/diff_trans"), std::string::npos) << range;
}
