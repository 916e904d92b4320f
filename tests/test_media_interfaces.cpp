// Medium boundaries that touch other surfaces: a smoke box standing on the floor, a glass
// ball full of smoke resting on it, a medium box inside a medium box (all three on the
// floor), each against the same scene with the boundaries lifted clear (1e-3 and 2e-3 of the
// box size of 555). Independent renders (other seeds), compared with `compare_images`'
// z-tests on both variances: the images must be the same up to noise.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "render_film.h"
#include "shading/trace.h"
#include "temp_dir.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/image/compare.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

// The Cornell box's walls, its light, and `objects` (JSON) inside; lift1 / lift2 are
// substituted for LIFT1 / LIFT2 in them.
std::string cornell_with(std::string objects, float lift1, float lift2) {
    auto put = [&](const std::string& key, float value) {
        for (size_t at; (at = objects.find(key)) != std::string::npos;)
            objects.replace(at, key.size(), std::to_string(value));
    };
    put("LIFT1", lift1);
    put("LIFT2", lift2);
    return R"({
      "camera": {"look_from": [278, 278, -800], "look_at": [278, 278, 0], "vfov": 40},
      "materials": {
        "red": {"type": "lambertian", "albedo": [0.65, 0.05, 0.05]},
        "white": {"type": "lambertian", "albedo": [0.73, 0.73, 0.73]},
        "green": {"type": "lambertian", "albedo": [0.12, 0.45, 0.15]},
        "glass": {"type": "dielectric", "ior": 1.5},
        "light": {"type": "diffuse_light", "radiance": [7, 7, 7]}},
      "media": {"smoke": {"density": 0.01, "albedo": [0, 0, 0]},
                "fog": {"density": 0.01, "albedo": [1, 1, 1]},
                "haze": {"density": 0.004, "albedo": [0.9, 0.8, 0.7]}},
      "objects": [
        {"type": "quad", "q": [555, 0, 0], "u": [0, 0, 555], "v": [0, 555, 0], "material": "green"},
        {"type": "quad", "q": [0, 0, 555], "u": [0, 0, -555], "v": [0, 555, 0], "material": "red"},
        {"type": "quad", "q": [113, 554, 127], "u": [330, 0, 0], "v": [0, 0, 305], "material": "light"},
        {"type": "quad", "q": [0, 555, 0], "u": [555, 0, 0], "v": [0, 0, 555], "material": "white"},
        {"type": "quad", "q": [0, 0, 555], "u": [555, 0, 0], "v": [0, 0, -555], "material": "white"},
        {"type": "quad", "q": [555, 0, 555], "u": [-555, 0, 0], "v": [0, 555, 0], "material": "white"},
        )" +
           objects + "]}";
}

struct Rendered {
    Image mean, variance;
};

Rendered render(const TempDir& dir, const std::string& json, uint64_t seed) {
    Scene scene = load_scene(dir.write("scene.json", json));
    Bvh bvh = Bvh::build(scene);
    RenderRequest c;
    c.width = 64;
    c.height = 64;
    c.spp = 256;
    c.seed = seed;
    c.estimator.max_depth = 50;
    Film film = wavefront_film(scene, bvh, c);
    return {film.mean(), film.variance_of_mean()};
}

// Touching (lifts 0) against lifted clear, both renders independent.
void expect_same_as_lifted(const char* what, const std::string& objects) {
    TempDir dir;
    const Rendered touching = render(dir, cornell_with(objects, 0.0f, 0.0f), 1);
    const Rendered lifted = render(dir, cornell_with(objects, 0.555f, 1.11f), 2);
    const ImageComparison c =
        compare_images(touching.mean, lifted.mean, &touching.variance, &lifted.variance);
    std::printf(
        "media-interfaces %-22s touching/lifted mean %.5f / %.5f, image z %.2f %.2f %.2f, worst "
        "block z %.2f, %d of %d tests failed\n",
        what, c.mean_ours, c.mean_ref, c.image_z[0], c.image_z[1], c.image_z[2], c.worst.z,
        c.failed, c.tests);
    EXPECT_TRUE(c.pass) << what;
}

}  // namespace

TEST(MediaInterfaces, SmokeBoxStandingOnTheFloor) {
    expect_same_as_lifted("smoke box on floor", R"(
        {"type": "box", "min": [0, 0, 0], "max": [165, 330, 165], "interior": "smoke",
         "transform": [{"rotate": {"axis": [0, 1, 0], "degrees": 15}},
                       {"translate": [265, LIFT1, 295]}]},
        {"type": "box", "min": [0, 0, 0], "max": [165, 165, 165], "interior": "fog",
         "transform": [{"rotate": {"axis": [0, 1, 0], "degrees": -18}},
                       {"translate": [130, LIFT1, 65]}]})");
}

TEST(MediaInterfaces, GlassBallOfSmokeRestingOnTheFloor) {
    expect_same_as_lifted("glass ball of smoke", R"(
        {"type": "sphere", "center": [278, 120, 278], "radius": 120, "material": "glass",
         "interior": "fog", "transform": [{"translate": [0, LIFT1, 0]}]})");
}

// Outer haze box and inner smoke box both standing on the floor: three coincident planes.
TEST(MediaInterfaces, MediumBoxInsideAMediumBoxOnTheFloor) {
    expect_same_as_lifted("box in box on floor", R"(
        {"type": "box", "min": [80, LIFT1, 80], "max": [480, 400, 480], "interior": "haze"},
        {"type": "box", "min": [180, LIFT2, 180], "max": [380, 250, 380], "interior": "fog"})");
}

// Without the margin a coincident boundary would be crossed through the floor: the touching
// scene came out 1% darker (z = -25) before boundaries were moved outwards. The margin itself
// is a hair: far below what the tests above could see.
TEST(MediaInterfaces, BoundaryMarginIsAHair) {
    const Aabb box{{100, 0, 100}, {400, 300, 400}};
    const float m = Scene::boundary_margin(box);
    EXPECT_GT(m, 4 * 400 * 1.2e-7f);  // well above the rounding of coordinates near 400
    EXPECT_LT(m, 1e-4f * 555);        // well below the lifts compared against
}

// Two overlapping spheres of one medium (density 0.5), a shadow ray through both along x:
// nested boundaries make one volume, x in [-1, 2], where Mitsuba's interface rule leaves the
// medium for vacuum on leaving the first sphere inside the second, x in [-1, 1] only.
TEST(MediaInterfaces, InterfaceBoundariesAreMitsubasRule) {
    TempDir dir;
    for (const char* rule : {"nested", "interface"}) {
        const auto path = dir.write("s.json", std::string(R"({"camera": {"look_from": [0, 0, 9],
            "look_at": [0, 0, 0]}, "media": {"m": {"density": 0.5, "albedo": 0.5}},
            "medium_boundaries": ")") + rule + R"(", "objects": [
            {"type": "sphere", "center": [0, 0, 0], "radius": 1, "interior": "m"},
            {"type": "sphere", "center": [1, 0, 0], "radius": 1, "interior": "m"}]})");
        const Scene s = load_scene(path);
        const Bvh bvh = Bvh::build(s);
        uint64_t rays = 0;
        const Ray ray{{-3, 0, 0}, {1, 0, 0}, 0.0f, 8.0f};
        const float tr = transmittance(s, bvh, ray, MediumStack{}, shadows_walk(s), &rays).x;
        // Boundaries are moved outwards by a hair (the margin): a tolerance of 1e-4.
        const float inside = std::string(rule) == "nested" ? 3.0f : 2.0f;
        EXPECT_NEAR(tr, std::exp(-0.5f * inside), 1e-4f) << rule;
    }
}
