#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "math/equal_area.h"
#include "ramp_image.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "wavetrace/image/image.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/surface.h"

using namespace wavetrace;

TEST(Texture, CheckerAlternatesInThreeDimensions) {
    Scene s;
    TextureId even = s.add_solid({1, 0, 0}), odd = s.add_solid({0, 0, 1});
    Texture t;
    t.kind = TextureKind::Checker;
    t.scale = 2.0f;
    t.even = even;
    t.odd = odd;
    TextureId c = s.add_texture(t);
    EXPECT_EQ(eval_texture(s, c, {}, {0.5f, 0.5f, 0.5f}), Color(1, 0, 0));
    EXPECT_EQ(eval_texture(s, c, {}, {2.5f, 0.5f, 0.5f}), Color(0, 0, 1));
    EXPECT_EQ(eval_texture(s, c, {}, {2.5f, 2.5f, 0.5f}), Color(1, 0, 0));
    EXPECT_EQ(eval_texture(s, c, {}, {-0.5f, 0.5f, 0.5f}), Color(0, 0, 1));
}

// The uv checkerboard alternates over (u, v) after its uv transform: scale 0.5 is Mitsuba's
// checkerboard (color0 = even in [0, 0.5)^2); a 90-degree turn and an offset move the cells.
TEST(Texture, UvCheckerAlternatesOverUvAfterItsTransform) {
    Scene s;
    TextureId even = s.add_solid({1, 0, 0}), odd = s.add_solid({0, 0, 1});
    Texture t;
    t.kind = TextureKind::UvChecker;
    t.scale = 0.5f;
    t.even = even;
    t.odd = odd;
    const TextureId c = s.add_texture(t);
    const Point3 far{100, 200, 300};  // the 3-D position plays no part
    EXPECT_EQ(eval_texture(s, c, {0.2f, 0.3f}, far), Color(1, 0, 0));
    EXPECT_EQ(eval_texture(s, c, {0.7f, 0.3f}, far), Color(0, 0, 1));
    EXPECT_EQ(eval_texture(s, c, {0.7f, 0.8f}, far), Color(1, 0, 0));
    EXPECT_EQ(eval_texture(s, c, {-0.2f, 0.3f}, far), Color(0, 0, 1));
    // u' = -v, v' = u (a quarter turn), then u' + 0.5.
    t.uv[0][0] = 0;
    t.uv[0][1] = -1;
    t.uv[0][2] = 0.5f;
    t.uv[1][0] = 1;
    t.uv[1][1] = 0;
    const TextureId turned = s.add_texture(t);
    // (0.2, 0.3) -> (0.2, 0.2): even; (0.2, 0.8) -> (-0.3, 0.2): odd.
    EXPECT_EQ(eval_texture(s, turned, {0.2f, 0.3f}, far), Color(1, 0, 0));
    EXPECT_EQ(eval_texture(s, turned, {0.2f, 0.8f}, far), Color(0, 0, 1));
    EXPECT_TRUE(texture_reads_uv(s, turned));
}

// An image's uv transform as the scene file writes it: scale, then rotate, then offset.
TEST(Texture, UvTransformsAreReadInOrder) {
    TempDir dir;
    const std::string scene = R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "lambertian", "albedo": {"type": "uv_checker", "scale": 1,
            "even": 0.2, "odd": 0.8,
            "uv_transform": {"scale": [2, 1], "rotate": 90, "offset": [0.25, 0]}}}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
    const Scene s = load_scene(dir.write("uv.json", scene));
    const Texture& t = s.textures[s.materials[0].albedo];
    // (u, v) -> scale (2u, v) -> rotate (-v, 2u) -> offset (-v + 0.25, 2u).
    const Vec2 st = t.map_uv({0.3f, 0.1f});
    EXPECT_NEAR(st.x, -0.1f + 0.25f, 1e-6f);
    EXPECT_NEAR(st.y, 0.6f, 1e-6f);
    const std::string bad = R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "lambertian", "albedo": {"type": "uv_checker", "scale": 1,
            "even": 0.2, "odd": 0.8, "uv_transform": {"scale": [2, 0]}}}},
        "objects": []})";
    try {
        load_scene(dir.write("bad.json", bad));
        ADD_FAILURE() << "a zero uv scale loaded";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("/materials/m/albedo/uv_transform/scale: a uv scale "
                                             "must not be 0"),
                  std::string::npos)
            << e.what();
    }
}

TEST(Texture, ImageIsBilinearAndWraps) {
    ImageData img;
    img.width = 2;
    img.height = 1;
    img.texels = {Color(0.0f), Color(1.0f)};
    auto at = [&](float u) {
        return img.lookup(u, 0.5f, TextureFilter::Bilinear, TextureWrap::Repeat, TextureWrap::Repeat).x;
    };
    // Texel centres at u = 0.25 and 0.75; halfway between them is the mean.
    EXPECT_FLOAT_EQ(at(0.25f), 0.0f);
    EXPECT_FLOAT_EQ(at(0.75f), 1.0f);
    EXPECT_FLOAT_EQ(at(0.5f), 0.5f);
    // u = 0 lies halfway between the last and the first texel (wrapping).
    EXPECT_FLOAT_EQ(at(0.0f), 0.5f);
    EXPECT_FLOAT_EQ(at(1.25f), 0.0f);
}

// A row of four texels 0, 1, 2, 3 looked up in each filter and wrap mode, inside and outside
// [0, 1], as Mitsuba's bitmap and pbrt-v4's imagemap define them: wraps act on texel indices.
TEST(Texture, FiltersAndWrapModesActOnTexels) {
    ImageData img;
    img.width = 4;
    img.height = 1;
    img.texels = {Color(0.0f), Color(1.0f), Color(2.0f), Color(3.0f)};
    auto at = [&](float u, TextureFilter f, TextureWrap w) {
        return img.lookup(u, 0.5f, f, w, TextureWrap::Repeat).x;
    };
    using F = TextureFilter;
    using W = TextureWrap;
    // Nearest: the texel u falls in; outside, texel -1 is 3 (repeat), 0 (mirror, clamp).
    EXPECT_EQ(at(0.3f, F::Nearest, W::Repeat), 1.0f);
    EXPECT_EQ(at(-0.1f, F::Nearest, W::Repeat), 3.0f);
    EXPECT_EQ(at(-0.1f, F::Nearest, W::Mirror), 0.0f);
    EXPECT_EQ(at(-0.1f, F::Nearest, W::Clamp), 0.0f);
    // Texels 4..7 past the right edge mirror to 3, 2, 1, 0; clamped, all are 3.
    EXPECT_EQ(at(1.3f, F::Nearest, W::Mirror), 2.0f);
    EXPECT_EQ(at(1.9f, F::Nearest, W::Mirror), 0.0f);
    EXPECT_EQ(at(2.1f, F::Nearest, W::Mirror), 0.0f);  // the next period starts unmirrored
    EXPECT_EQ(at(1.9f, F::Nearest, W::Clamp), 3.0f);
    EXPECT_EQ(at(1e9f, F::Nearest, W::Clamp), 3.0f);
    // Bilinear at the left edge, halfway between texel -1 and texel 0.
    EXPECT_FLOAT_EQ(at(0.0f, F::Bilinear, W::Repeat), 1.5f);
    EXPECT_FLOAT_EQ(at(0.0f, F::Bilinear, W::Mirror), 0.0f);
    EXPECT_FLOAT_EQ(at(0.0f, F::Bilinear, W::Clamp), 0.0f);
    // Past the right edge: between texels 4 and 5 (at u = 1.25): 2.5 mirrored, 3 clamped.
    EXPECT_FLOAT_EQ(at(1.25f, F::Bilinear, W::Mirror), 2.5f);
    EXPECT_FLOAT_EQ(at(1.25f, F::Bilinear, W::Clamp), 3.0f);
    // Black: nothing beyond the image; half of texel 0 at its edge.
    EXPECT_EQ(at(-0.1f, F::Nearest, W::Black), 0.0f);
    EXPECT_EQ(at(1.1f, F::Nearest, W::Black), 0.0f);
    EXPECT_FLOAT_EQ(at(1.0f, F::Bilinear, W::Black), 1.5f);
    // Inside, away from the edges, every wrap agrees.
    for (W w : {W::Repeat, W::Mirror, W::Clamp, W::Black})
        EXPECT_FLOAT_EQ(at(0.5f, F::Bilinear, w), 1.5f);
}

// The two axes wrap each by its own mode (glTF's wrapS and wrapT): a 2 x 2 image whose columns
// hold 0 and 1 and whose rows add 0 (top) and 10 (bottom), looked up past both edges.
TEST(Texture, EachAxisWrapsByItsOwnMode) {
    ImageData img;
    img.width = img.height = 2;
    img.texels = {Color(0.0f), Color(1.0f), Color(10.0f), Color(11.0f)};
    using W = TextureWrap;
    auto at = [&](float u, float v, W wu, W wv) {
        return img.lookup(u, v, TextureFilter::Nearest, wu, wv).x;
    };
    // u = 1.25 is column 2: clamped to 1, repeated to 0. v = -0.25 is row 2 from the top:
    // clamped to the bottom row (1), mirrored to it too, repeated to the top row (0).
    EXPECT_EQ(at(1.25f, -0.25f, W::Clamp, W::Repeat), 1.0f);
    EXPECT_EQ(at(1.25f, -0.25f, W::Repeat, W::Clamp), 10.0f);
    EXPECT_EQ(at(1.25f, -0.25f, W::Clamp, W::Mirror), 11.0f);
    EXPECT_EQ(at(1.25f, -0.25f, W::Repeat, W::Repeat), 0.0f);
    // Bilinear too: halfway between columns 1 and 2 at u = 1, rows in range.
    EXPECT_FLOAT_EQ(img.lookup(1.0f, 0.75f, TextureFilter::Bilinear, W::Clamp, W::Repeat).x, 1.0f);
    EXPECT_FLOAT_EQ(img.lookup(1.0f, 0.75f, TextureFilter::Bilinear, W::Repeat, W::Clamp).x, 0.5f);
}

// An image's luminance gradient is the derivative of its bilinear interpolation inside the
// texel cell (a difference quotient over a step that stays in the cell agrees), also through a
// texture's uv map and colour factor; 0 with the nearest filter.
TEST(Texture, ImageGradientIsTheCellsDerivative) {
    Scene s;
    ImageData img;
    img.width = 5;
    img.height = 3;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    for (int k = 0; k < img.width * img.height; ++k)
        img.texels.push_back(Color(u01(rng), u01(rng), u01(rng)));
    Texture t;
    t.kind = TextureKind::Image;
    t.image = s.add_image(img);
    t.factor = Color(0.5f, 2.0f, 1.0f);
    // st = A uv + b: turned by 30 degrees, scaled by 1.5 along s.
    t.uv[0][0] = 1.5f * 0.8660254f;
    t.uv[0][1] = -1.5f * 0.5f;
    t.uv[0][2] = 0.1f;
    t.uv[1][0] = 0.5f;
    t.uv[1][1] = 0.8660254f;
    t.uv[1][2] = 0.2f;
    const TextureId id = s.add_texture(t);
    const double h = 1e-3;
    auto lum = [&](double u, double v) {
        return double(luminance(eval_texture(s, id, {float(u), float(v)}, {})));
    };
    for (const Vec2 uv : {Vec2{0.31f, 0.47f}, Vec2{0.72f, 0.13f}, Vec2{0.05f, 0.88f}}) {
        Vec2 g;
        ASSERT_TRUE(texture_luminance_gradient(s, id, uv, &g));
        const double du = (lum(uv.x + h, uv.y) - lum(uv.x - h, uv.y)) / (2 * h);
        const double dv = (lum(uv.x, uv.y + h) - lum(uv.x, uv.y - h)) / (2 * h);
        EXPECT_NEAR(g.x, du, 2e-3 * (1 + std::fabs(du))) << uv.x << ", " << uv.y;
        EXPECT_NEAR(g.y, dv, 2e-3 * (1 + std::fabs(dv))) << uv.x << ", " << uv.y;
    }
    s.textures[id].filter = TextureFilter::Nearest;
    Vec2 g;
    ASSERT_TRUE(texture_luminance_gradient(s, id, {0.31f, 0.47f}, &g));
    EXPECT_EQ(g.x, 0.0f);
    EXPECT_EQ(g.y, 0.0f);
    EXPECT_FALSE(texture_luminance_gradient(s, s.add_solid(Color(0.5f)), {0.3f, 0.3f}, &g));
}

TEST(Texture, NoiseIsDeterministicBoundedAndVaries) {
    float lo = 1e9f, hi = -1e9f;
    for (int i = 0; i < 2000; ++i) {
        Point3 p{i * 0.37f, i * 0.11f, i * -0.23f};
        float n = perlin_noise(p);
        EXPECT_EQ(n, perlin_noise(p));
        lo = std::min(lo, n);
        hi = std::max(hi, n);
        EXPECT_GE(perlin_turbulence(p), 0.0f);
    }
    EXPECT_GE(lo, -1.0f);
    EXPECT_LE(hi, 1.0f);
    EXPECT_GT(hi - lo, 0.5f);
    EXPECT_EQ(perlin_noise({3, 4, 5}), 0.0f);  // gradient noise vanishes on the lattice
}

TEST(Texture, EarthImageIsDecodedFromSrgb) {
    Scene s = load_scene(scene_path("everything"));
    ASSERT_EQ(s.images.size(), 1u);
    const ImageData& earth = s.images[0];
    EXPECT_EQ(earth.width, 1024);
    EXPECT_EQ(earth.height, 512);
    for (const Color& c : earth.texels) {
        ASSERT_GE(min_component(c), 0.0f);
        ASSERT_LE(max_component(c), 1.0f);
    }
}

namespace {
// A one-texel image texture.
TextureId add_image_texture(Scene& s) {
    ImageData img;
    img.width = img.height = 1;
    img.texels = {Color(0.5f)};
    Texture image;
    image.kind = TextureKind::Image;
    image.image = s.add_image(img);
    return s.add_texture(image);
}
}  // namespace

// Only image textures read uv, directly or as a checker's cell; surface_at computes a sphere's
// uv (an acos and an atan2) only for such materials.
TEST(Texture, OnlyImagesReadUv) {
    Scene s;
    const TextureId solid = s.add_solid({1, 0, 0}), picture = add_image_texture(s);
    Texture noise;
    noise.kind = TextureKind::Noise;
    Texture checker;
    checker.kind = TextureKind::Checker;
    checker.even = solid;
    checker.odd = solid;
    const TextureId plain_checker = s.add_texture(checker);
    checker.odd = picture;
    EXPECT_FALSE(texture_reads_uv(s, kNone));
    EXPECT_FALSE(texture_reads_uv(s, solid));
    EXPECT_FALSE(texture_reads_uv(s, s.add_texture(noise)));
    EXPECT_FALSE(texture_reads_uv(s, plain_checker));
    EXPECT_TRUE(texture_reads_uv(s, picture));
    EXPECT_TRUE(texture_reads_uv(s, s.add_texture(checker)));
}

TEST(Surface, SphereUvFollowsTheSeed) {
    Scene s;
    Material textured;
    textured.albedo = add_image_texture(s);
    s.add_material(textured);
    s.add_sphere({{0, 0, 0}, 1, 0, kNone});
    Hit hit{1.0f, PrimRef::make(PrimKind::Sphere, 0)};
    // The point (1, 0, 0): theta = pi/2, phi = pi -> (0.5, 0.5).
    SurfaceHit h = surface_at(s, Ray{{2, 0, 0}, {-1, 0, 0}}, hit);
    EXPECT_NEAR(h.uv.x, 0.5f, 1e-6f);
    EXPECT_NEAR(h.uv.y, 0.5f, 1e-6f);
    EXPECT_TRUE(h.front_face);
    EXPECT_NEAR(h.ng.x, 1.0f, 1e-6f);
    // From inside the ray arrives at the back.
    SurfaceHit inside = surface_at(s, Ray{{0, 0, 0}, {1, 0, 0}}, hit);
    EXPECT_FALSE(inside.front_face);
}

// Every texture of a material counts: a rough conductor's alpha, a principled material's weight.
TEST(Surface, SphereUvForEveryTextureOfItsMaterial) {
    Scene s;
    Material rough;
    rough.kind = MaterialKind::Conductor;
    rough.albedo = s.add_solid({1, 1, 1});
    rough.alpha_u_texture = rough.alpha_v_texture = add_image_texture(s);
    Material principled;
    principled.kind = MaterialKind::Principled;
    principled.albedo = s.add_solid({0.5f, 0.5f, 0.5f});
    principled.principled.sheen.texture = add_image_texture(s);
    s.add_material(rough);
    s.add_material(principled);
    s.add_sphere({{0, 0, 0}, 1, 0, kNone});
    s.add_sphere({{0, 0, 0}, 1, 1, kNone});
    for (uint32_t i = 0; i < 2; ++i) {
        const Hit hit{1.0f, PrimRef::make(PrimKind::Sphere, i)};
        const SurfaceHit h = surface_at(s, Ray{{2, 0, 0}, {-1, 0, 0}}, hit);
        EXPECT_NEAR(h.uv.x, 0.5f, 1e-6f) << "material " << i;
        EXPECT_NEAR(h.uv.y, 0.5f, 1e-6f) << "material " << i;
    }
}

TEST(Background, EnvironmentMapIsLatLongWithMinusZAtTheCentre) {
    TempDir dir;
    // Four columns of grey 0, 1, 2, 3 in the top row, 10 more in the bottom row (HDR values
    // survive EXR).
    const Image env = ramp_image(4, 2);
    write_image(dir.path() / "env.exr", env);
    auto p = dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "background": {"type": "environment", "file": "env.exr", "scale": [2, 2, 2]},
        "objects": []})");
    Scene s = load_scene(p);
    ASSERT_EQ(s.background.kind, Background::Kind::Environment);
    // Column centres sit at u = 1/8, 3/8, 5/8, 7/8; -z maps to u = 1/2, +x to 3/4, -x to 1/4,
    // +z to the seam at u = 0 = 1.
    // At the horizon the two rows mix equally (+5).
    EXPECT_NEAR(eval_background(s, {0, 0, -1}).x, 2 * (1.5f + 5), 1e-5f);
    EXPECT_NEAR(eval_background(s, {1, 0, 0}).x, 2 * (2.5f + 5), 1e-5f);
    EXPECT_NEAR(eval_background(s, {-1, 0, 0}).x, 2 * (0.5f + 5), 1e-5f);
    EXPECT_NEAR(eval_background(s, {0, 0, 1}).x, 2 * (1.5f + 5), 1e-5f);
    // The poles are clamped to the top and bottom rows, not wrapped into each other.
    EXPECT_NEAR(eval_background(s, {0, 3, 0}).x, 2 * 1.5f, 1e-5f);
    EXPECT_NEAR(eval_background(s, {0, -3, 0}).x, 2 * 11.5f, 1e-5f);
}

// pbrt-v4's equal-area map: square, looked up at the nearest texel, in the frame `to_world`
// gives (here the map's +z is world +y and its +y world -z, as pbrt scenes turn their sky).
TEST(Background, EqualAreaMapIsSeenThroughItsFrame) {
    TempDir dir;
    const Image env = ramp_image(4, 4);
    write_image(dir.path() / "sky.exr", env);
    write_image(dir.path() / "wide.exr", Image(8, 4));
    auto scene = [&](const std::string& background) {
        return dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
            "background": )" + background + R"(, "objects": []})");
    };
    Scene s = load_scene(scene(R"({"type": "environment", "file": "sky.exr", "scale": 2,
        "mapping": "equal_area", "to_world": [[1, 0, 0], [0, 0, 1], [0, -1, 0]]})"));
    ASSERT_EQ(s.background.mapping, Background::Mapping::EqualArea);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const Vec3 l = equal_area_square_to_sphere((x + 0.5f) / 4, (y + 0.5f) / 4);
            EXPECT_EQ(eval_background(s, {l.x, l.z, -l.y}).x, 2.0f * (x + 10 * y)) << x << y;
        }
    auto error = [&](const std::string& background) {
        try {
            load_scene(scene(background));
        } catch (const SceneError& e) {
            return std::string(e.what());
        }
        return std::string("(no error)");
    };
    std::string err = error(R"({"type": "environment", "file": "wide.exr", "mapping": "equal_area"})");
    EXPECT_NE(err.find("/background/file: an equal_area map must be square; '"), std::string::npos) << err;
    EXPECT_NE(err.find("wide.exr' is 8 x 4"), std::string::npos) << err;
    err = error(R"({"type": "environment", "file": "sky.exr", "mapping": "equal_area", "rotation": 90})");
    EXPECT_NE(err.find("/background/rotation: \"rotation\" applies to latlong maps only"),
              std::string::npos) << err;
    err = error(R"({"type": "environment", "file": "sky.exr", "to_world": [[1, 0, 0], [0, 2, 0], [0, 0, 1]]})");
    EXPECT_NE(err.find("/background/to_world: expected a rotation"), std::string::npos) << err;
    err = error(R"({"type": "environment", "file": "sky.exr", "mapping": "cube"})");
    EXPECT_NE(err.find("/background/mapping: unknown mapping \"cube\""), std::string::npos) << err;
}

// A latitude-longitude map turned by `to_world` (here its pole to world +z): the direction
// that sees the map's top row is the frame's +y.
TEST(Background, LatLongMapTurnsWithItsFrame) {
    TempDir dir;
    const Image env = ramp_image(4, 2);
    write_image(dir.path() / "env.exr", env);
    auto p = dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "background": {"type": "environment", "file": "env.exr",
                       "to_world": [[1, 0, 0], [0, 0, -1], [0, 1, 0]]}, "objects": []})");
    Scene s = load_scene(p);
    EXPECT_NEAR(eval_background(s, {0, 0, 3}).x, 1.5f, 1e-5f);    // the map's +y: top row
    EXPECT_NEAR(eval_background(s, {0, 0, -3}).x, 11.5f, 1e-5f);  // its -y: the bottom row
    // The map's -z (the image centre at the horizon) is world +y.
    EXPECT_NEAR(eval_background(s, {0, 1, 0}).x, 1.5f + 5, 1e-5f);
}

// `illuminance` scales a map so that a surface facing its pole receives that illuminance:
// checked against an independent Monte Carlo integral of the looked-up radiance over the
// hemisphere about the frame's pole (fixed seed; 400,000 directions, about 0.2% error).
TEST(Background, IlluminanceScalesTheMapToMeetIt) {
    TempDir dir;
    auto fill = [&](const char* name, int w, int h, auto value) {
        Image img(w, h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) img.at(x, y) = value(x, y);
        write_image(dir.path() / name, img);
    };
    fill("gradient-ea.exr", 32, 32, [](int x, int y) { return Color(1 + x, 2 + y, 0.5f); });
    fill("gradient-ll.exr", 64, 32, [](int x, int y) { return Color(0.5f, 1 + x, 1 + y); });
    // Bright only where the equal-area map's texel centres lie below its horizon.
    fill("below.exr", 16, 16, [](int x, int y) {
        return Color(equal_area_square_to_sphere((x + 0.5f) / 16, (y + 0.5f) / 16).z > 0 ? 1 : 100);
    });
    fill("one.exr", 16, 16, [](int, int) { return Color(1); });
    fill("black.exr", 4, 4, [](int, int) { return Color(0); });
    auto load = [&](const std::string& background) {
        return load_scene(dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
            "background": )" + background + R"(, "objects": []})"));
    };
    auto illuminance = [](const Scene& s, Vec3 pole) {
        const Frame f = Frame::from_normal(pole);
        std::mt19937 rng(7);
        std::uniform_real_distribution<float> u01(0.0f, 1.0f);
        double sum = 0;
        const int n = 400000;
        for (int i = 0; i < n; ++i) {  // uniform on the hemisphere: pdf 1 / 2 pi
            const float z = u01(rng), phi = 2 * kPi * u01(rng), r = std::sqrt(1 - z * z);
            const Vec3 d = f.to_world({r * std::cos(phi), r * std::sin(phi), z});
            sum += luminance(eval_background(s, d)) * z;
        }
        return sum * 2 * kPi / n;
    };
    // The map's +z is world -y here; the lat-long map's +y (its top row) is world +x.
    Scene ea = load(R"({"type": "environment", "file": "gradient-ea.exr", "mapping": "equal_area",
        "illuminance": 5, "to_world": [[1, 0, 0], [0, 0, -1], [0, 1, 0]]})");
    EXPECT_NEAR(illuminance(ea, {0, -1, 0}), 5.0, 0.05);
    Scene ll = load(R"({"type": "environment", "file": "gradient-ll.exr", "illuminance": 5,
        "to_world": [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]})");
    EXPECT_NEAR(illuminance(ll, {1, 0, 0}), 5.0, 0.05);
    Scene poles = load(R"({"type": "environment", "file": "gradient-ll.exr", "illuminance": 5,
        "rows_at_poles": true, "scale": 2})");
    EXPECT_NEAR(illuminance(poles, {0, 1, 0}), 10.0, 0.1);
    // Only the upper hemisphere counts.
    const Scene below = load(R"({"type": "environment", "file": "below.exr", "mapping": "equal_area", "illuminance": 2})");
    const Scene one = load(R"({"type": "environment", "file": "one.exr", "mapping": "equal_area", "illuminance": 2})");
    EXPECT_EQ(below.background.radiance.x, one.background.radiance.x);
    // Texels straddling the horizon count whole or not at all: 1.6% at 16 x 16.
    EXPECT_NEAR(one.background.radiance.x, 2 / kPi, 0.02 * 2 / kPi);
    try {
        load(R"({"type": "environment", "file": "black.exr", "illuminance": 2})");
        ADD_FAILURE() << "a black map was scaled";
    } catch (const SceneError& e) {
        const std::string err = e.what();
        EXPECT_NE(err.find("/background/illuminance: the map '"), std::string::npos) << err;
        EXPECT_NE(err.find("black.exr' is black above its horizon"), std::string::npos) << err;
    }
}

TEST(Texture, ProductMultipliesItsFactors) {
    TempDir dir;
    const auto p = dir.write("p.json", R"({"camera": {"look_from": [0, 0, 3], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "lambertian", "albedo": {"type": "product", "factors": [
          [0.5, 0.25, 1], {"type": "checker", "scale": 1, "even": 0.5, "odd": [1, 0.5, 0.2]}]}}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
    const Scene s = load_scene(p);
    const TextureId t = s.materials[0].albedo;
    EXPECT_EQ(eval_texture(s, t, {}, {0.5f, 0.5f, 0.5f}), Color(0.25f, 0.125f, 0.5f));
    EXPECT_EQ(eval_texture(s, t, {}, {1.5f, 0.5f, 0.5f}), Color(0.5f, 0.125f, 0.2f));
    EXPECT_EQ(texture_mean(s, t), Color(0.5f, 0.25f, 1) * Color(0.75f, 0.5f, 0.35f));
    // A reflectance's factors are reflectances.
    dir.write("q.json", R"({"camera": {"look_from": [0, 0, 3], "look_at": [0, 0, 0]},
      "materials": {"m": {"type": "lambertian", "albedo": {"type": "product", "factors": [2, 0.1]}}},
      "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})");
    EXPECT_THROW(load_scene(dir.path() / "q.json"), SceneError);
}
