// Blends of two materials (Mitsuba 3's blendbsdf, pbrt-v4's mix): each hit takes one of them,
// the second with probability w, so that the image's expectation is that of the mixture
// (1 - w) f0 + w f1. Against a mixture that is itself a material (two diffuse surfaces blend
// into the diffuse surface of the mixed albedo) the images agree up to noise; where w is 0 or 1
// the choice is certain and the image is the other material's exactly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "render_film.h"
#include "temp_dir.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/image/compare.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

// A floor, a sphere on it and a wall, all of material "m" from `materials` (JSON members),
// lit by a quad light above.
std::string scene_with(const std::string& materials) {
    return R"({
      "camera": {"look_from": [0, 2, -6], "look_at": [0, 0.8, 0], "vfov": 40},
      "materials": {"light": {"type": "diffuse_light", "radiance": [6, 6, 6]}, )" +
           materials + R"(},
      "objects": [
        {"type": "quad", "q": [-3, 0, -3], "u": [6, 0, 0], "v": [0, 0, 6], "material": "m"},
        {"type": "quad", "q": [-3, 0, 2], "u": [6, 0, 0], "v": [0, 4, 0], "material": "m"},
        {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "m"},
        {"type": "quad", "q": [-1, 4, -1], "u": [2, 0, 0], "v": [0, 0, 2], "material": "light"}]})";
}

Film render(const TempDir& dir, const std::string& materials, uint64_t seed, Engine engine) {
    const Scene scene = load_scene(dir.write("scene.json", scene_with(materials)).string());
    const Bvh bvh = Bvh::build(scene);
    RenderRequest r;
    r.width = 40;
    r.height = 32;
    r.spp = 128;
    r.seed = seed;
    r.estimator.max_depth = 5;
    return engine == Engine::Wavefront ? wavefront_film(scene, bvh, r)
                                       : megakernel_film(scene, bvh, r);
}

bool same_pixels(const Image& a, const Image& b) {
    return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
           std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(a.pixels[0])) ==
               0;
}

std::string load_error(const std::string& materials) {
    TempDir dir;
    try {
        load_scene(dir.write("scene.json", scene_with(materials)).string());
        return "";
    } catch (const std::exception& e) {
        return e.what();
    }
}

}  // namespace

// 0.7 red + 0.3 blue diffuse, as a blend and as one diffuse surface, in independent renders
// (other seeds): the z-tests of compare on both variances pass, in both engines.
TEST(Blend, OfTwoDiffuseSurfacesIsTheDiffuseSurfaceOfTheMixedAlbedo) {
    TempDir dir;
    const std::string blend = R"(
        "red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]},
        "m": {"type": "blend", "weight": 0.3,
              "materials": ["red", {"type": "lambertian", "albedo": [0.1, 0.2, 0.9]}]})";
    const std::string mixed = R"("m": {"type": "lambertian", "albedo": [0.59, 0.13, 0.34]})";
    for (const Engine engine : {Engine::Megakernel, Engine::Wavefront}) {
        const Film a = render(dir, blend, 1, engine);
        const Film b = render(dir, mixed, 2, engine);
        const Image va = a.variance_of_mean(), vb = b.variance_of_mean();
        const ImageComparison c = compare_images(a.mean(), b.mean(), &va, &vb);
        std::printf("blend/mixed mean %.5f / %.5f, image z %.2f %.2f %.2f, %d of %d tests failed\n",
                    c.mean_ours, c.mean_ref, c.image_z[0], c.image_z[1], c.image_z[2], c.failed,
                    c.tests);
        EXPECT_TRUE(c.pass);
    }
}

// A weight of 0 and 1 in a checkerboard's cells: each cell is one material for certain, and
// the image is bit for bit that of a checkerboard albedo of the two. On a blend of weight 0.4,
// a glossy metal and a diffuse surface, the engines make the same choices: every pixel channel
// within rounding (1e-4 relative) of the other's, where one choice made differently would
// change a pixel by far more.
TEST(Blend, CertainChoicesAreThatMaterialAndTheEnginesAgree) {
    TempDir dir;
    const std::string checker =
        R"({"type": "uv_checker", "scale": 0.25, "even": EVEN, "odd": ODD})";
    auto cells = [&](const std::string& even, const std::string& odd) {
        std::string s = checker;
        s.replace(s.find("EVEN"), 4, even);
        s.replace(s.find("ODD"), 3, odd);
        return s;
    };
    const std::string blend =
        R"("red": {"type": "lambertian", "albedo": [0.8, 0.1, 0.1]},
           "blue": {"type": "lambertian", "albedo": [0.1, 0.2, 0.9]},
           "m": {"type": "blend", "materials": ["red", "blue"], "weight": )" +
        cells("0", "1") + "}";
    const std::string albedo = R"("m": {"type": "lambertian", "albedo": )" +
                               cells("[0.8, 0.1, 0.1]", "[0.1, 0.2, 0.9]") + "}";
    EXPECT_TRUE(same_pixels(render(dir, blend, 3, Engine::Megakernel).mean(),
                            render(dir, albedo, 3, Engine::Megakernel).mean()));
    const std::string glossy = R"(
        "gold": {"type": "metal", "albedo": [0.9, 0.7, 0.3], "roughness": 0.2},
        "m": {"type": "blend", "weight": 0.4,
              "materials": [{"type": "lambertian", "albedo": 0.5}, "gold"]})";
    const Image mk = render(dir, glossy, 4, Engine::Megakernel).mean();
    const Image wv = render(dir, glossy, 4, Engine::Wavefront).mean();
    size_t outside = 0, values = 0;
    double sum_mk = 0, sum_wv = 0;
    for (size_t i = 0; i < mk.pixels.size(); ++i)
        for (int k = 0; k < 3; ++k, ++values) {
            const double a = mk.pixels[i][k], b = wv.pixels[i][k], diff = std::fabs(a - b);
            sum_mk += a;
            sum_wv += b;
            if (diff > 1e-6 && diff > 1e-4 * std::fabs(a)) ++outside;
        }
    std::printf("engines: %zu of %zu channels apart, means %.7f / %.7f\n", outside, values, sum_mk,
                sum_wv);
    EXPECT_EQ(outside, 0u);
    EXPECT_LE(std::fabs(sum_mk - sum_wv), 1e-5 * sum_mk);
}

// Blends nest; what cannot be decided at the hit is refused, naming the material.
TEST(Blend, SceneFileNamesWhatItRefuses) {
    EXPECT_EQ(load_error(R"("a": {"type": "lambertian", "albedo": 0.5},
        "b": {"type": "blend", "materials": ["a", {"type": "mirror"}]},
        "m": {"type": "blend", "weight": 0.2, "materials": ["b", "a"]})"),
              "");
    const std::string cycle = load_error(R"(
        "m": {"type": "blend", "materials": ["n", "m"]},
        "n": {"type": "blend", "materials": ["m", "m"]})");
    EXPECT_NE(cycle.find("contains itself"), std::string::npos) << cycle;
    const std::string unknown = load_error(R"("m": {"type": "blend", "materials": ["x", "x"]})");
    EXPECT_NE(unknown.find("/materials/m/materials/0"), std::string::npos) << unknown;
    EXPECT_NE(unknown.find("no material named \"x\""), std::string::npos) << unknown;
    const std::string one = load_error(R"("m": {"type": "blend", "materials": ["light"]})");
    EXPECT_NE(one.find("expected two materials"), std::string::npos) << one;
    const std::string range = load_error(
        R"("m": {"type": "blend", "weight": 1.5,
              "materials": [{"type": "mirror"}, {"type": "mirror"}]})");
    EXPECT_NE(range.find("/materials/m/weight"), std::string::npos) << range;
    const std::string emits =
        load_error(R"("m": {"type": "blend", "materials": ["light", {"type": "mirror"}]})");
    EXPECT_NE(emits.find("/materials/m/materials/0"), std::string::npos) << emits;
    EXPECT_NE(emits.find("cannot emit"), std::string::npos) << emits;
}
