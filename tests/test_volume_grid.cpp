// Grid media: the exact optical depth of grid_track.h against numerical integration of the
// grid's own lookup, flights that end where the depth runs out, and Mitsuba's .vol files read
// strictly (the reference tests match Mitsuba's images of them: docs/validation.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "formats/volume_file.h"
#include "media/grid_track.h"
#include "temp_dir.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

VolumeGrid random_grid(int nx, int ny, int nz, int channels, std::mt19937& rng) {
    std::uniform_real_distribution<float> value(0.0f, 2.0f);
    VolumeGrid g;
    g.res[0] = nx;
    g.res[1] = ny;
    g.res[2] = nz;
    g.channels = channels;
    g.values.resize(static_cast<size_t>(nx) * ny * nz * channels);
    for (float& v : g.values) v = value(rng);
    // Placed turned, stretched and moved, as a scene's to_world places it.
    const Transform to_world = Transform::translate({-0.4f, 0.2f, 0.1f}) *
                               Transform::rotate({1.0f, 2.0f, 0.5f}, 33.0f) *
                               Transform::scale({1.3f, 0.7f, 1.1f});
    g.to_local = to_world.inverse();
    return g;
}

// The depth along the ray by the midpoint rule over the grid's lookup, zero outside its box.
Color numeric_depth(const VolumeGrid& g, Color scale, Point3 o, Vec3 dir, float length) {
    const int steps = 40000;
    const double h = double(length) / steps;
    double sum[3] = {0, 0, 0};
    for (int i = 0; i < steps; ++i) {
        const Point3 p = o + float((i + 0.5) * h) * dir;
        const Point3 q = g.to_local.point(p);
        if (q.x < 0 || q.x > 1 || q.y < 0 || q.y > 1 || q.z < 0 || q.z > 1) continue;
        const Color v = g.lookup_local(q) * scale;
        for (int c = 0; c < 3; ++c) sum[c] += v[c] * h;
    }
    return {float(sum[0]), float(sum[1]), float(sum[2])};
}

TEST(VolumeGrids, OpticalDepthIsTheIntegralOfTheInterpolation) {
    std::mt19937 rng(7);
    const Color scale{1.0f, 0.5f, 2.0f};
    struct Mode {
        int channels;
        bool nearest;
        TextureWrap wrap;
    };
    for (const Mode mode :
         {Mode{1, false, TextureWrap::Clamp}, Mode{3, false, TextureWrap::Clamp},
          Mode{3, false, TextureWrap::Repeat}, Mode{1, false, TextureWrap::Mirror},
          Mode{3, true, TextureWrap::Clamp}, Mode{1, true, TextureWrap::Repeat},
          Mode{3, false, TextureWrap::Black}}) {
        const int channels = mode.channels;
        VolumeGrid g = random_grid(5, 4, 3, channels, rng);
        g.nearest = mode.nearest;
        g.wrap = mode.wrap;
        int crossing = 0;
        for (int ray = 0; ray < 40; ++ray) {
            // From a point around the box through another: most rays cross it, some miss.
            std::uniform_real_distribution<float> u(-0.6f, 1.4f);
            const Transform to_world = g.to_local.inverse();
            const Point3 a = to_world.point({u(rng), u(rng), u(rng)});
            const Point3 b = to_world.point({u(rng), u(rng), u(rng)});
            const Vec3 dir = normalize(b - a);
            const float length = 1.2f * wavetrace::length(b - a);
            const Color exact = grid_reach(g, scale, a, dir, length, 0, kInfinity).depth;
            const Color numeric = numeric_depth(g, scale, a, dir, length);
            if (max_component(numeric) > 0.0f) ++crossing;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(exact[c], numeric[c], 2e-3f * numeric[c] + 1e-5f)
                    << "channels " << channels << " nearest " << mode.nearest << " wrap "
                    << int(mode.wrap) << " ray " << ray << " channel " << c;
        }
        EXPECT_GT(crossing, 20);
    }
}

TEST(VolumeGrids, FlightsEndWhereTheirDepthRunsOut) {
    std::mt19937 rng(11);
    const VolumeGrid g = random_grid(6, 5, 4, 3, rng);
    const Color scale{3.0f, 1.0f, 0.5f};
    const Point3 o = g.to_local.inverse().point({-0.3f, 0.45f, 0.5f});
    const Vec3 dir = normalize(g.to_local.inverse().point({1.3f, 0.55f, 0.45f}) - o);
    const float length = 4.0f;
    const Color total = grid_reach(g, scale, o, dir, length, 0, kInfinity).depth;
    for (int c = 0; c < 3; ++c) {
        ASSERT_GT(total[c], 0.5f);
        for (float fraction : {0.0f, 0.01f, 0.3f, 0.77f, 0.999f}) {
            const GridReach r = grid_reach(g, scale, o, dir, length, c, fraction * total[c]);
            ASSERT_TRUE(r.reached);
            EXPECT_NEAR(r.depth[c], fraction * total[c], 1e-4f * total[c]);
            // The depth up to where it stopped, for every channel, and the extinction there.
            const Color numeric = numeric_depth(g, scale, o, dir, r.dist);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.depth[k], numeric[k], 2e-3f * total[k]);
            const Color there = g.lookup(o + r.dist * dir) * scale;
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(r.sigma[k], there[k], 1e-4f * scale[k]);
        }
        EXPECT_FALSE(grid_reach(g, scale, o, dir, length, c, 1.001f * total[c]).reached);
    }
    // Along a ray that misses the box nothing is crossed.
    const GridReach miss = grid_reach(g, scale, o + Vec3{0, 50, 0}, dir, kInfinity, 0, 0.5f);
    EXPECT_FALSE(miss.reached);
    EXPECT_EQ(max_component(miss.depth), 0.0f);
}

std::string vol_file(int nx,
                     int ny,
                     int nz,
                     int channels,
                     const std::vector<float>& values,
                     int version = 3,
                     int encoding = 1) {
    std::string s = "VOL";
    s += char(version);
    auto put = [&](const void* p, size_t n) { s.append(static_cast<const char*>(p), n); };
    for (int32_t v : {int32_t(encoding), int32_t(nx), int32_t(ny), int32_t(nz), int32_t(channels)})
        put(&v, 4);
    for (float b : {0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f}) put(&b, 4);
    put(values.data(), values.size() * 4);
    return s;
}

TEST(VolumeGrids, VolFilesAreReadStrictly) {
    TempDir dir;
    const VolumeGrid g =
        read_volume_file(dir.write("g.vol", vol_file(2, 1, 1, 3, {1, 2, 3, 4, 5, 6})));
    EXPECT_EQ(g.res[0], 2);
    EXPECT_EQ(g.channels, 3);
    EXPECT_EQ(g.voxel(1, 0, 0).z, 6.0f);
    // The centre of the far voxel, and beyond it the edge value (clamp).
    EXPECT_EQ(g.lookup_local({0.75f, 0.5f, 0.5f}).x, 4.0f);
    EXPECT_EQ(g.lookup_local({3.0f, -2.0f, 9.0f}).y, 5.0f);
    EXPECT_NEAR(g.lookup_local({0.5f, 0.5f, 0.5f}).y, 3.5f, 1e-6f);
    // Beyond the grid, repeated (x 1.25 is 0.25) or mirrored (x 1.25 is 0.75, -0.25 is 0.25).
    VolumeGrid w = g;
    w.wrap = TextureWrap::Repeat;
    EXPECT_EQ(w.lookup_local({1.25f, 0.5f, 0.5f}).x, g.lookup_local({0.25f, 0.5f, 0.5f}).x);
    // Between the last centre and the edge, interpolated towards the first voxel.
    EXPECT_NEAR(w.lookup_local({0.875f, 0.5f, 0.5f}).x, 0.75f * 4.0f + 0.25f * 1.0f, 1e-6f);
    w.wrap = TextureWrap::Mirror;
    EXPECT_EQ(w.lookup_local({1.25f, 0.5f, 0.5f}).x, g.lookup_local({0.75f, 0.5f, 0.5f}).x);
    EXPECT_EQ(w.lookup_local({-0.25f, 0.5f, 0.5f}).x, g.lookup_local({0.25f, 0.5f, 0.5f}).x);
    // Nearest: each voxel's value over its cell.
    w.nearest = true;
    EXPECT_EQ(w.lookup_local({0.49f, 0.5f, 0.5f}).x, 1.0f);
    EXPECT_EQ(w.lookup_local({0.51f, 0.5f, 0.5f}).x, 4.0f);

    auto error_of = [&](const std::string& bytes) {
        try {
            read_volume_file(dir.write("bad.vol", bytes));
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(error_of("VOL").find("shorter than the 48-byte header"), std::string::npos);
    EXPECT_NE(error_of("XYZ" + vol_file(1, 1, 1, 1, {1}).substr(3)).find("VOL"), std::string::npos);
    EXPECT_NE(error_of(vol_file(1, 1, 1, 1, {1}, 2)).find("version 2 at byte 3"),
              std::string::npos);
    EXPECT_NE(error_of(vol_file(1, 1, 1, 1, {1}, 3, 4)).find("encoding 4 at byte 4"),
              std::string::npos);
    EXPECT_NE(error_of(vol_file(1, 0, 1, 1, {})).find("y resolution 0 at byte 12"),
              std::string::npos);
    EXPECT_NE(error_of(vol_file(1, 1, 1, 2, {1, 1})).find("2 channels at byte 20"),
              std::string::npos);
    // A header claiming far more than the file holds fails before any allocation.
    EXPECT_NE(error_of(vol_file(1 << 30, 1 << 30, 1 << 30, 3, {1})).find("claims far more"),
              std::string::npos);
    EXPECT_NE(error_of(vol_file(2, 2, 1, 1, {1, 1, 1})).find("claims 16"), std::string::npos);
    EXPECT_NE(error_of(vol_file(2, 2, 1, 1, {1, 1, -1, 1})).find("voxel (0, 1, 0)"),
              std::string::npos);
    EXPECT_NE(error_of(vol_file(1, 1, 1, 1, {NAN})).find("finite and >= 0"), std::string::npos);
}

TEST(VolumeGrids, SceneFilesPlaceGridsAndCheckTheirRange) {
    TempDir dir;
    dir.write("d.vol", vol_file(2, 1, 1, 1, {0.5f, 3.0f}));
    const std::string scene =
        R"({"camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0], "vfov": 40},
            "media": {"fog": {"density": 2, "albedo": ALBEDO,
                              "density_grid": {"file": "d.vol",
                                               "transform": [{"scale": 2}, {"translate": [-1, -1, -1]}]}}},
            "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
                         "interior": "fog"}]})";
    auto with = [&](const std::string& albedo) {
        std::string s = scene;
        s.replace(s.find("ALBEDO"), 6, albedo);
        return dir.write("s.json", s);
    };
    const Scene s = load_scene(with(R"({"type": "grid", "value": [0.9, 0.5, 0.1]})"));
    ASSERT_EQ(s.media.size(), 1u);
    ASSERT_TRUE(s.media[0].heterogeneous());
    const VolumeGrid& g = s.volume_grids[s.media[0].density_grid];
    EXPECT_NEAR(g.lookup({-0.5f, 0.0f, 0.0f}).x, 0.5f, 1e-6f);  // the centre of voxel 0
    EXPECT_NEAR(g.lookup({0.5f, 0.0f, 0.0f}).x, 3.0f, 1e-6f);
    // Reflectances must stay within [0, 1]; a missing file names itself and the place.
    try {
        load_scene(with(R"({"type": "grid", "file": "d.vol"})"));
        ADD_FAILURE() << "a grid albedo of 3 loaded";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("must not exceed 1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("/media/fog/albedo/file"), std::string::npos)
            << e.what();
    }
    std::string missing = scene;
    missing.replace(missing.find("d.vol"), 5, "none.vol");
    missing.replace(missing.find("ALBEDO"), 6, "0.5");
    try {
        load_scene(dir.write("m.json", missing));
        ADD_FAILURE() << "a missing grid loaded";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("none.vol"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace wavetrace
