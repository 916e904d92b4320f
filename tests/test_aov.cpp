#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "test_paths.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/engines/aov.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/surface.h"

using namespace wavetrace;

TEST(Aov, CornellAlbedoSeesTheWalls) {
    Scene scene = load_scene(scene_path("cornell"));
    Bvh bvh = Bvh::build(scene);
    Image img = render_aov(scene, bvh, Aov::Albedo, {60, 60, 1, 0});
    // The camera's right is cross(up, backwards) = -x: the green wall (x = 555) is on the left.
    EXPECT_EQ(img.at(2, 30), Color(0.12f, 0.45f, 0.15f));
    EXPECT_EQ(img.at(57, 30), Color(0.65f, 0.05f, 0.05f));
    EXPECT_EQ(img.at(30, 5), Color(0.73f, 0.73f, 0.73f));  // the ceiling
}

TEST(Aov, DepthAndNormalOfThePlainBackWall) {
    Scene scene = load_scene(scene_path("cornell"));
    Bvh bvh = Bvh::build(scene);
    // Pixel (30, 20) of 61 x 61 sees the back wall (z = 555) above the tall block.
    Image depth = render_aov(scene, bvh, Aov::Depth, {61, 61, 1, 0});
    Image normal = render_aov(scene, bvh, Aov::Normal, {61, 61, 1, 0});
    Ray r = CameraRays(scene.camera, 61, 61).generate(30.5f, 20.5f, 0.5f, 0.5f);
    float expected = (555.0f - r.o.z) / r.d.z * length(r.d);
    EXPECT_NEAR(depth.at(30, 20).x, expected, 1e-3f * expected);
    EXPECT_EQ(normal.at(30, 20), Color(0, 0, -1));
}

TEST(Aov, MediumBoundariesAreLookedThrough) {
    // In cornell-smoke the blocks are only media: the albedo AOV sees the floor behind them.
    Scene scene = load_scene(scene_path("cornell-smoke"));
    Bvh bvh = Bvh::build(scene);
    Image img = render_aov(scene, bvh, Aov::Albedo, {40, 40, 1, 0});
    CameraRays camera(scene.camera, 40, 40);
    int through_medium = 0;
    for (int y = 0; y < 40; ++y)
        for (int x = 0; x < 40; ++x) {
            Ray ray = camera.generate(x + 0.5f, y + 0.5f, 0.5f, 0.5f);
            Hit first = bvh.intersect(ray);
            if (!first.found()) continue;
            if (scene.materials[scene.prim_material(first.prim)].kind != MaterialKind::Interface)
                continue;
            ++through_medium;
            // Behind a block there is always a white floor or wall.
            EXPECT_EQ(img.at(x, y), Color(0.73f, 0.73f, 0.73f)) << x << " " << y;
        }
    EXPECT_GT(through_medium, 100);
}

TEST(Aov, ResultDoesNotDependOnThreadCount) {
    Scene scene = load_scene(scene_path("everything"));
    Bvh bvh = Bvh::build(scene);
    auto render = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return render_aov(scene, bvh, Aov::Normal, {80, 80, 4, 42});
    };
    Image one = render(1), two = render(2), many = render(5);
    EXPECT_EQ(one.pixels.size(), two.pixels.size());
    for (size_t i = 0; i < one.pixels.size(); ++i) {
        ASSERT_EQ(one.pixels[i], two.pixels[i]) << i;
        ASSERT_EQ(one.pixels[i], many.pixels[i]) << i;
    }
}
