// Mitsuba 3 XML scenes: each element lands in the Scene where Mitsuba's manual says it acts
// (sensor, film, sampler, integrator, shapes, transforms, BSDFs, emitters, spectra), the
// parameter, include and 0.6-upgrade machinery works, bad input names the file and line, what
// cannot be represented is a warning with its place, and `convert` writes a JSON scene that
// renders bit-identically.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "load_warnings.h"
#include "formats/spectrum_rgb.h"
#include "ramp_image.h"
#include "temp_dir.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/image/image.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"
#include "wavetrace/shading/surface.h"

using namespace wavetrace;

namespace {


double degrees(double radians) { return radians * 180.0 / 3.14159265358979323846; }

// A scene around `body` with a camera, as Mitsuba 3 writes one.
std::string scene(const std::string& body, const std::string& version = "3.0.0") {
    return "<scene version=\"" + version + "\">\n" + body + "\n</scene>\n";
}

std::string error_of(const std::filesystem::path& path, const LoadOptions& options = {}) {
    try {
        load_scene(path, options);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

std::string read(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(MitsubaScenes, SensorFilmSamplerAndIntegratorSetTheRender) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(
  <integrator type="moment"><integrator type="path">
    <integer name="max_depth" value="5"/></integrator></integrator>
  <sensor type="perspective">
    <float name="fov" value="60"/>
    <transform name="to_world"><lookat origin="1, 2, 3" target="1, 2, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="32"/>
      <rfilter type="box"/></film>
    <sampler type="independent"><integer name="sample_count" value="7"/></sampler>
  </sensor>
  <shape type="sphere"/>)"));
    Scene s = load_scene(path, collecting());
    EXPECT_EQ(s.render.width, 64);
    EXPECT_EQ(s.render.height, 32);
    EXPECT_EQ(s.render.spp, 7);
    EXPECT_EQ(s.render.max_depth, 5);
    EXPECT_EQ(s.render.sampler, SamplerKind::Independent);
    EXPECT_NEAR(s.camera.look_from.x, 1.0f, 1e-6f);
    EXPECT_NEAR(s.camera.look_from.z, 3.0f, 1e-6f);
    EXPECT_LT(s.camera.look_at.z, 3.0f);  // looking down -z
    // fov_axis x (the default) on a 2:1 film: the vertical field is narrower.
    EXPECT_NEAR(s.camera.vfov, degrees(2 * std::atan(std::tan(30.0 * 3.14159265358979 / 180) / 2)),
                1e-3);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
}

// A stratified or low-discrepancy sampler becomes the Sobol sampler, with a warning.
TEST(MitsubaScenes, LowDiscrepancySamplersDrawSobolPoints) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(
  <sensor type="perspective">
    <sampler type="ldsampler"><integer name="sample_count" value="16"/></sampler>
  </sensor>
  <shape type="sphere"/>)"));
    Scene s = load_scene(path, collecting());
    EXPECT_EQ(s.render.sampler, SamplerKind::Sobol);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("sampler \"ldsampler\": wavetrace draws Owen-scrambled Sobol points"),
              std::string::npos)
        << warnings[0];
}

// A sensor whose to_world mirrors (x scaled by -1) sees the world as Mitsuba renders it: our
// camera then reverses the image's x axis.
TEST(MitsubaScenes, AMirroringSensorGivesAMirroredCamera) {
    TempDir dir;
    for (const char* scale : {"1", "-1"}) {
        auto path = dir.write("a.xml", scene(std::string(R"(
  <sensor type="perspective"><transform name="to_world">
    <scale x=")") + scale + R"("/><lookat origin="0, 0, 5" target="0, 0, 0" up="0, 1, 0"/>
  </transform></sensor>
  <shape type="sphere"/>)"));
        Scene s = load_scene(path, collecting());
        EXPECT_EQ(s.camera.mirror, std::string(scale) == "-1") << scale;
    }
}

TEST(MitsubaScenes, DefaultFocalLengthKeepsTheDiagonalOf35mmFilm) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(<sensor type="perspective">
    <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="48"/>
    <rfilter type="box"/></film></sensor><shape type="sphere"/>)"));
    Scene s = load_scene(path, collecting());
    // 50 mm on a 36 x 24 mm frame: 46.79 degrees on the diagonal, 34.02 vertically on a square.
    EXPECT_NEAR(s.camera.vfov, 34.0221, 1e-3);
    EXPECT_EQ(s.render.max_depth, kMaxDepth);  // no integrator: Mitsuba's path, unbounded
}

TEST(MitsubaScenes, ShapesTransformsAndMaterialsTranslate) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(
  <bsdf type="diffuse" id="red"><rgb name="reflectance" value="0.8, 0.1, 0.1"/></bsdf>
  <shape type="sphere">
    <point name="center" x="1" y="0" z="0"/><float name="radius" value="0.5"/>
    <ref id="red"/>
  </shape>
  <shape type="sphere">
    <transform name="to_world"><matrix value="2 0 0 3  0 2 0 0  0 0 2 0  0 0 0 1"/></transform>
    <bsdf type="twosided"><bsdf type="roughconductor"><string name="material" value="Au"/>
      <float name="alpha" value="0.2"/></bsdf></bsdf>
  </shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="2"/><translate z="-1"/></transform>
    <bsdf type="roughplastic"><rgb name="diffuse_reflectance" value="0.3"/></bsdf>
  </shape>)"));
    Scene s = load_scene(path, collecting());
    ASSERT_EQ(s.spheres.size(), 2u);
    EXPECT_NEAR(s.spheres[0].center.x, 1.0f, 1e-6f);
    EXPECT_NEAR(s.spheres[0].radius, 0.5f, 1e-6f);
    EXPECT_NEAR(s.spheres[1].center.x, 3.0f, 1e-6f);  // the matrix's translation
    EXPECT_NEAR(s.spheres[1].radius, 2.0f, 1e-6f);
    const Material& red = s.materials[s.spheres[0].material];
    EXPECT_EQ(red.kind, MaterialKind::Lambertian);
    EXPECT_TRUE(red.one_sided);  // Mitsuba's diffuse is black from behind
    EXPECT_NEAR(s.textures[red.albedo].color.x, 0.8f, 1e-6f);
    const Material& gold = s.materials[s.spheres[1].material];
    EXPECT_EQ(gold.kind, MaterialKind::Conductor);
    EXPECT_FALSE(gold.one_sided);  // twosided
    EXPECT_EQ(gold.distribution, Microfacet::Beckmann);  // roughconductor's default
    EXPECT_NEAR(gold.alpha_u, 0.2f, 1e-6f);
    ASSERT_EQ(s.quads.size(), 1u);
    EXPECT_NEAR(s.quads[0].q.x, -2.0f, 1e-6f);
    EXPECT_NEAR(s.quads[0].q.z, -1.0f, 1e-6f);
    const Material& plastic = s.materials[s.quads[0].material];
    EXPECT_EQ(plastic.kind, MaterialKind::Plastic);
    EXPECT_NEAR(plastic.alpha_u, 0.1f, 1e-6f);  // roughplastic's defaults: Beckmann, 0.1
    EXPECT_EQ(plastic.distribution, Microfacet::Beckmann);
    EXPECT_NEAR(plastic.ior, 1.49f / 1.000277f, 1e-5f);  // polypropylene in air
}

// Textures sit where Mitsuba puts them: at its uv of each shape, (u, v) = ((x + 1) / 2,
// (y + 1) / 2) on a rectangle, a PLY's uv as in the file, an OBJ's as (u, 1 - v), on the cube's
// +z face ((y + 1) / 2, (x + 1) / 2) (its vertices (1, -1, 1), (1, 1, 1), (-1, 1, 1), (-1, -1, 1)
// carry uv (0, 1), (1, 1), (1, 0), (0, 0)), on a sphere (phi / 2 pi, theta / pi) about its own
// +z, on a cylinder (phi / 2 pi, the fraction of its axis); then `to_uv`; then an image's texel in column u W
// and row v H from the top, a checkerboard's color0 where u and v (mod 1) lie on the same side
// of 0.5. The image's texel (i, j) holds i + 10 j; each point is a texel centre.
// A bitmap's filter_type and wrap_mode become the texture's filter and wrap, without a
// warning; a filter Mitsuba has and we do not is one.
TEST(MitsubaScenes, BitmapFiltersAndWrapModesAreKept) {
    TempDir dir;
    write_image(dir.path() / "t.exr", ramp_image(4, 4));
    auto bitmap = [](const char* filter, const char* wrap) {
        return std::string(R"(<shape type="rectangle"><bsdf type="diffuse">
      <texture name="reflectance" type="bitmap"><string name="filename" value="t.exr"/>
      <string name="filter_type" value=")") + filter + R"("/><string name="wrap_mode" value=")" +
               wrap + R"("/></texture></bsdf></shape>)";
    };
    auto path = dir.write("a.xml", scene("<sensor type=\"perspective\"/>" +
                                         bitmap("nearest", "mirror") + bitmap("bilinear", "clamp") +
                                         bitmap("bilinear", "repeat")));
    Scene s = load_scene(path, collecting());
    for (const std::string& w : warnings) ADD_FAILURE() << w;
    std::vector<std::pair<TextureFilter, TextureWrap>> images;
    for (const Texture& t : s.textures)
        if (t.kind == TextureKind::Image) {
            images.emplace_back(t.filter, t.wrap_u);
            EXPECT_EQ(t.wrap_v, t.wrap_u);
        }
    const std::vector<std::pair<TextureFilter, TextureWrap>> expected = {
        {TextureFilter::Nearest, TextureWrap::Mirror},
        {TextureFilter::Bilinear, TextureWrap::Clamp},
        {TextureFilter::Bilinear, TextureWrap::Repeat}};
    EXPECT_EQ(images, expected);
    path = dir.write("b.xml", scene(bitmap("lanczos", "repeat")));
    load_scene(path, collecting());
    EXPECT_TRUE(warned("filter_type \"lanczos\" is not supported; bilinear is used"));
}

TEST(MitsubaScenes, TexturesSitWhereMitsubaPutsThem) {
    TempDir dir;
    const Image img = ramp_image(4, 4);
    write_image(dir.path() / "t.exr", img);
    const std::string square = "-1 -1 0 0 0\n1 -1 0 1 0\n1 1 0 1 1\n-1 1 0 0 1\n";
    dir.write("m.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n"
                       "property float y\nproperty float z\nproperty float u\nproperty float v\n"
                       "element face 2\nproperty list uchar int vertex_indices\nend_header\n" +
                           square + "3 0 1 2\n3 0 2 3\n");
    dir.write("m.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                       "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    const std::string image = R"(<bsdf type="diffuse"><texture name="reflectance" type="bitmap">
      <string name="filename" value="t.exr"/><boolean name="raw" value="true"/>)";
    auto at = [](int x) { return "<transform name=\"to_world\"><translate x=\"" +
                                 std::to_string(x) + "\"/></transform>"; };
    auto path = dir.write("a.xml", scene(R"(<sensor type="perspective"/>
  <shape type="rectangle">)" + at(0) + image + R"(</texture></bsdf></shape>
  <shape type="rectangle">)" + at(3) + image + R"(
      <transform name="to_uv"><scale x="2"/><translate x="0.125" y="0.5"/></transform>
    </texture></bsdf></shape>
  <shape type="rectangle">)" + at(6) + R"(<bsdf type="diffuse">
    <texture name="reflectance" type="checkerboard"><rgb name="color0" value="0.25"/>
      <rgb name="color1" value="0.75"/></texture></bsdf></shape>
  <shape type="ply"><string name="filename" value="m.ply"/>)" + at(9) + image + R"(</texture></bsdf></shape>
  <shape type="obj"><string name="filename" value="m.obj"/>)" + at(12) + image + R"(</texture></bsdf></shape>
  <shape type="cube">)" + at(15) + image + R"(</texture></bsdf></shape>
  <shape type="sphere"><float name="radius" value="0.5"/>
    <transform name="to_world"><rotate x="1" angle="90"/><translate x="18"/></transform>)" +
                                             image + R"(</texture></bsdf></shape>
  <shape type="cylinder"><float name="radius" value="0.5"/>)" + at(21) + image +
                                             R"(</texture></bsdf></shape>)"));
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_FALSE(s.geometric_side_test);  // Mitsuba's BSDFs answer in the shading frame
    const Bvh bvh = Bvh::build(s);
    // The texture's value seen along a ray, by default from above at (x, y) (the cube's top
    // face at z = 1).
    auto seen_along = [&](const Ray& ray) {
        const Hit hit = bvh.intersect(ray);
        EXPECT_TRUE(hit.found()) << ray.o.x << ", " << ray.o.y;
        if (!hit.found()) return -1.0f;
        const SurfaceHit h = surface_at(s, ray, hit);
        return eval_texture(s, s.materials[h.material].albedo, h.uv, h.p).x;
    };
    auto seen = [&](float x, float y) { return seen_along(Ray{{x, y, 3}, {0, 0, -1}}); };
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const float u = (i + 0.5f) / 4, v = (j + 0.5f) / 4;  // Mitsuba's uv there
            const float texel = i + 10.0f * j;
            // Rectangle: (x, y) = (2u - 1, 2v - 1).
            EXPECT_EQ(seen(2 * u - 1, 2 * v - 1), texel) << "rectangle " << i << j;
            // to_uv: u' = 2u + 0.125, v' = v + 0.5 (mod 1).
            const float u2 = std::fmod(2 * u + 0.125f, 1.0f), v2 = std::fmod(v + 0.5f, 1.0f);
            EXPECT_EQ(seen(3 + 2 * u - 1, 2 * v - 1),
                      std::floor(u2 * 4) + 10 * std::floor(v2 * 4)) << "to_uv " << i << j;
            EXPECT_EQ(seen(6 + 2 * u - 1, 2 * v - 1), (u > 0.5f) == (v > 0.5f) ? 0.25f : 0.75f)
                << "checkerboard " << i << j;
            // PLY: the file's uv (u, v) = ((x + 1) / 2, (y + 1) / 2); OBJ: v = 1 - file's.
            EXPECT_EQ(seen(9 + 2 * u - 1, 2 * v - 1), texel) << "ply " << i << j;
            EXPECT_EQ(seen(12 + 2 * u - 1, 1 - 2 * v), texel) << "obj " << i << j;
            // Cube, +z face: (x, y) = (2v - 1, 2u - 1).
            EXPECT_EQ(seen(15 + 2 * v - 1, 2 * u - 1), texel) << "cube " << i << j;
            // Sphere: its local n = (sin theta cos phi, sin theta sin phi, cos theta) at
            // (u, v) = (phi / 2 pi, theta / pi), turned by to_world (+y to +z, +z to -y).
            const float phi = 2 * 3.14159265f * u, theta = 3.14159265f * v;
            const Vec3 local{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                             std::cos(theta)};
            const Vec3 n{local.x, -local.z, local.y};
            const Point3 centre{18, 0, 0};
            EXPECT_NEAR(seen_along(Ray{centre + 2.0f * n, -n}), texel, 1e-3f) << "sphere " << i << j;
            // Cylinder (p0 at the origin, p1 = +z): (cos phi, sin phi, v) at (phi / 2 pi, v).
            const Vec3 out{std::cos(phi), std::sin(phi), 0.0f};
            EXPECT_NEAR(seen_along(Ray{Point3{21, 0, v} + 2.0f * out, -out}), texel, 1e-2f)
                << "cylinder " << i << j;
        }
}

// Mitsuba's checkerboard has two phases: looked up as a colour (Texture::eval) color0 lies where
// u and v (mod 1) are on the same side of 0.5, looked up as a number (eval_1: a roughness, an
// opacity) where they are on different sides; its reference images hold both.
TEST(MitsubaScenes, ACheckerboardOfNumbersHasMitsubasOtherPhase) {
    TempDir dir;
    const std::string checker = R"(type="checkerboard"><float name="color0" value="0.05"/>
      <float name="color1" value="0.3"/></texture>)";
    // The masked rectangle lies out of the rays' way (a mask cuts the surface away for them);
    // its opacity is looked up at the other's uv, the same on both.
    const auto path = dir.write("a.xml", scene(R"(<sensor type="perspective"/>
  <shape type="rectangle"><bsdf type="roughconductor"><texture name="alpha_u" )" + checker + R"(
      <float name="alpha_v" value="0.1"/><texture name="specular_reflectance" )" + checker + R"(
    </bsdf></shape>
  <shape type="rectangle"><transform name="to_world"><translate x="3"/></transform>
    <bsdf type="mask"><texture name="opacity" )" + checker + R"(<bsdf type="diffuse"/></bsdf>
  </shape>)"));
    const Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    const Bvh bvh = Bvh::build(s);
    TextureId opacity = kNone;
    for (const Material& m : s.materials)
        if (m.opacity != kNone) opacity = m.opacity;
    ASSERT_NE(opacity, kNone);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const float u = (i + 0.5f) / 4, v = (j + 0.5f) / 4;  // Mitsuba's uv there
            const Ray ray{{2 * u - 1, 2 * v - 1, 3}, {0, 0, -1}};
            const Hit hit = bvh.intersect(ray);
            ASSERT_TRUE(hit.found());
            const SurfaceHit h = surface_at(s, ray, hit);
            const Material& m = s.materials[h.material];
            ASSERT_NE(m.alpha_u_texture, kNone);
            const bool same_side = (u > 0.5f) == (v > 0.5f);
            auto at = [&](TextureId t) { return eval_texture(s, t, h.uv, h.p).x; };
            EXPECT_EQ(at(m.albedo), same_side ? 0.05f : 0.3f) << "colour " << i << j;
            EXPECT_EQ(at(m.alpha_u_texture), same_side ? 0.3f : 0.05f) << "alpha_u " << i << j;
            EXPECT_EQ(at(opacity), same_side ? 0.3f : 0.05f) << "opacity " << i << j;
        }
}

// normalmap and bumpmap correct the mapped normal as Mitsuba 3 does by default (flipped where
// it faces away, Estevez et al.'s shadowing), each switch as its property says.
TEST(MitsubaScenes, MappedNormalsTakeMitsubasCorrections) {
    TempDir dir;
    auto materials = [&](const std::string& props) {
        const auto path = dir.write("m.xml", scene(R"(<sensor type="perspective"/>
  <shape type="rectangle"><bsdf type="normalmap">)" +
                                                   props + R"(
      <rgb name="normalmap" value="0.5, 0.5, 1"/><bsdf type="diffuse"/></bsdf></shape>
  <shape type="sphere"><bsdf type="bumpmap">)" + props +
                                                   R"(
      <texture type="checkerboard"/><bsdf type="diffuse"/></bsdf></shape>)"));
        return load_scene(path, collecting()).materials;
    };
    int mapped = 0;
    for (const Material& m : materials("")) {
        if (!m.has_normal_maps()) continue;
        ++mapped;
        EXPECT_TRUE(m.flip_invalid_normals);
        EXPECT_TRUE(m.bump_shadowing);
    }
    EXPECT_EQ(mapped, 2);
    for (const Material& m : materials(R"(<boolean name="flip_invalid_normals" value="false"/>
        <boolean name="use_shadowing_function" value="false"/>)")) {
        EXPECT_FALSE(m.flip_invalid_normals);
        EXPECT_FALSE(m.bump_shadowing);
    }
    EXPECT_TRUE(warnings.empty()) << warnings.front();
}

// mitsuba-data's various_shapes (before its sdfgrid) loads from its own file: every shape
// (sphere, cylinder, disk, rectangle, the rectangle as .serialized, OBJ and PLY, two cubes),
// warned only about the clip planes and the disk's texture coordinates.
TEST(MitsubaScenes, VariousShapesLoadEveryShape) {
    const std::filesystem::path path =
        std::filesystem::path(WAVETRACE_REFERENCE_DIR) /
        "mitsuba3/tests/scenes/various_shapes/test_various_shapes_path.xml";
    const Scene s = load_scene(path, collecting());
    EXPECT_EQ(warnings.size(), 2u);
    EXPECT_TRUE(warned("test_various_shapes_path.xml:12: warning: sensor: near_clip and far_clip"));
    EXPECT_TRUE(warned("test_various_shapes_path.xml:67: warning: disk: its texture coordinates"));
    EXPECT_EQ(s.spheres.size(), 1u);
    EXPECT_EQ(s.quads.size(), 13u);  // the rectangle, and six faces each cube
    EXPECT_EQ(s.meshes.size(), 5u);  // cylinder, disk, .serialized, OBJ, PLY
}

// blendbsdf becomes our blend of its two BSDFs, its weight a number or a texture (read as
// Mitsuba's eval_1 reads it); twosided around it makes both sides of each BSDF reflect. What
// the hit would have to decide before choosing (a mask) is refused, with its place.
TEST(MitsubaScenes, BlendbsdfBlendsItsTwoBsdfs) {
    TempDir dir;
    const auto path = dir.write("b.xml", scene(R"(<sensor type="perspective"/>
  <bsdf type="roughconductor" id="metal"/>
  <shape type="sphere"><bsdf type="twosided"><bsdf type="blendbsdf">
      <texture name="weight" type="checkerboard"/>
      <bsdf type="diffuse"/><ref id="metal"/></bsdf></bsdf></shape>
  <shape type="rectangle"><bsdf type="blendbsdf"><float name="weight" value="0.25"/>
      <bsdf type="diffuse"/><bsdf type="plastic"/></bsdf></shape>)"));
    const Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    int blends = 0;
    for (const Material& m : s.materials) {
        if (m.kind != MaterialKind::Blend) continue;
        ++blends;
        const Material &a = s.materials[m.blend[0]], &b = s.materials[m.blend[1]];
        EXPECT_EQ(a.kind, MaterialKind::Lambertian);
        if (m.blend_weight.texture != kNone) {  // the two-sided one
            EXPECT_EQ(s.textures[m.blend_weight.texture].kind, TextureKind::UvChecker);
            EXPECT_EQ(b.kind, MaterialKind::Conductor);
            EXPECT_FALSE(a.one_sided);
            EXPECT_FALSE(b.one_sided);
        } else {
            EXPECT_FLOAT_EQ(m.blend_weight.value, 0.25f);
            EXPECT_EQ(b.kind, MaterialKind::Plastic);
            EXPECT_TRUE(a.one_sided);
            EXPECT_TRUE(b.one_sided);
        }
    }
    EXPECT_EQ(blends, 2);
    auto one = dir.write("o.xml", scene(R"(<shape type="sphere"><bsdf type="blendbsdf">
      <float name="weight" value="0.5"/><bsdf type="diffuse"/></bsdf></shape>)"));
    EXPECT_NE(error_of(one).find("o.xml:2"), std::string::npos) << error_of(one);
    auto masked = dir.write("m.xml", scene(R"(<shape type="sphere"><bsdf type="blendbsdf">
      <float name="weight" value="0.5"/><bsdf type="diffuse"/>
      <bsdf type="mask"><bsdf type="diffuse"/></bsdf></bsdf></shape>)"));
    EXPECT_NE(error_of(masked).find("m.xml:4"), std::string::npos) << error_of(masked);
}

// Mitsuba's disk (the unit disk at z = 0 facing +z, −z with flip_normals) and cylinder (open,
// from p0 to p1, facing outwards) as tessellated meshes: where they are, which way they face,
// and their area (128 segments a turn: a disk n sin(2π/n)/(2π) of πr², a tube n sin(π/n)/π
// of 2πrh).
TEST(MitsubaScenes, DisksAndCylindersBecomeMeshesFacingTheirWay) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(<sensor type="perspective"/>
  <shape type="disk">
    <transform name="to_world"><scale value="2"/><translate z="3"/></transform>
    <boolean name="flip_normals" value="true"/>
    <emitter type="area"><rgb name="radiance" value="1"/></emitter>
  </shape>
  <shape type="cylinder">
    <point name="p0" x="1" y="0" z="0"/><point name="p1" x="1" y="0" z="4"/>
    <float name="radius" value="0.5"/>
  </shape>)"));
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_EQ(s.meshes.size(), 2u);
    const double pi = 3.14159265358979323846, n = 128;
    double area[2] = {0, 0};
    for (const Triangle& t : s.triangles) {
        const Vec3 a = s.positions[t.v[0]], b = s.positions[t.v[1]], c = s.positions[t.v[2]];
        const Vec3 g = cross(b - a, c - a);  // the front side's normal, twice the area long
        area[t.mesh] += 0.5 * length(g);
        const Vec3 centroid = (a + b + c) / 3.0f;
        if (t.mesh == 0) {
            EXPECT_NEAR(a.z, 3.0f, 1e-5f);
            EXPECT_LT(g.z, 0.0f) << "flip_normals: the disk faces -z";
            EXPECT_LE(std::hypot(centroid.x, centroid.y), 2.0f);
        } else {
            // Outwards: from the axis (x = 1, y = 0) towards the triangle.
            EXPECT_GT(dot(g, Vec3{centroid.x - 1.0f, centroid.y, 0.0f}), 0.0f);
            EXPECT_GE(centroid.z, 0.0f);
            EXPECT_LE(centroid.z, 4.0f);
        }
    }
    EXPECT_NEAR(area[0], pi * 4 * n * std::sin(2 * pi / n) / (2 * pi), 1e-4);
    EXPECT_NEAR(area[1], 2 * pi * 0.5 * 4 * n * std::sin(pi / n) / pi, 1e-4);
    // The disk is the scene's light; the cylinder shades round (vertex normals).
    EXPECT_TRUE(s.meshes[1].has_normals);
    EXPECT_EQ(s.materials[s.meshes[0].material].kind, MaterialKind::DiffuseLight);
}

// A spot's projected texture: Mitsuba's local +x is our right, its image rows run down from
// local -y, so our up is -y in the world (here the lookat's up, +z, turned over).
TEST(MitsubaScenes, SpotsKeepTheTextureTheyProject) {
    TempDir dir;
    write_image(dir.path() / "slide.exr", ramp_image(2, 2));
    auto path = dir.write("a.xml", scene(R"(<sensor type="perspective"/>
  <emitter type="spot"><transform name="to_world"><lookat origin="0,5,0" target="0,0,0" up="0,0,1"/></transform>
    <texture name="texture" type="bitmap"><string name="filename" value="slide.exr"/></texture>
    <rgb name="intensity" value="2"/></emitter>)"));
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    ASSERT_NE(l.texture, kNone);
    EXPECT_EQ(s.textures[l.texture].kind, TextureKind::Image);
    EXPECT_NEAR(l.up.z, -1.0f, 1e-6f);
    EXPECT_NEAR(l.direction.y, -1.0f, 1e-6f);
}

TEST(MitsubaScenes, EmittersBecomeLightsAndBackgrounds) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(
  <emitter type="point"><point name="position" x="0" y="4" z="0"/>
    <rgb name="intensity" value="10"/></emitter>
  <emitter type="spot"><transform name="to_world"><lookat origin="0,5,0" target="0,0,0"/></transform>
    <float name="cutoff_angle" value="30"/><rgb name="intensity" value="2"/></emitter>
  <emitter type="constant"><spectrum name="radiance" value="400:1, 700:1"/></emitter>
  <shape type="sphere"><emitter type="area"><rgb name="radiance" value="5, 4, 3"/></emitter></shape>)"));
    Scene s = load_scene(path, collecting());
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Point);
    EXPECT_NEAR(s.lights[0].intensity.y, 10.0f, 1e-6f);
    EXPECT_EQ(s.lights[1].kind, Light::Kind::Spot);
    EXPECT_NEAR(s.lights[1].direction.y, -1.0f, 1e-6f);
    EXPECT_NEAR(s.lights[1].cutoff_degrees, 30.0f, 1e-5f);
    EXPECT_NEAR(s.lights[1].falloff_start_degrees, 22.5f, 1e-5f);  // beam_width: 3/4 cutoff
    EXPECT_EQ(s.lights[1].texture, kNone);
    // A flat spectrum of 1 seen by sRGB: not quite white (sRGB's white is D65).
    const Color flat = spectrum_to_rgb({{400, 1}, {700, 1}}, false);
    EXPECT_EQ(s.background.kind, Background::Kind::Constant);
    EXPECT_NEAR(s.background.radiance.x, flat.x, 1e-6f);
    EXPECT_NEAR(s.background.radiance.z, flat.z, 1e-6f);
    const Material& lamp = s.materials[s.spheres[0].material];
    EXPECT_EQ(lamp.kind, MaterialKind::DiffuseLight);
}

// Mitsuba's envmap looks a direction up in its to_world frame at u = atan2(d.x, -d.z) / 2pi,
// v = acos(d.y) / pi, its rows from pole to pole; a to_world that turns the pole away from +y
// (here +90 degrees about x: the map's +y to world +z, its -z to world +y) keeps that frame.
TEST(MitsubaScenes, AnEnvmapTurnedAnyWayKeepsItsFrame) {
    TempDir dir;
    const Image env = ramp_image(4, 2);
    write_image(dir.path() / "env.exr", env);
    auto path = dir.write("a.xml", scene(R"(
  <emitter type="envmap"><string name="filename" value="env.exr"/>
    <transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>)"));
    Scene s = load_scene(path, collecting());
    EXPECT_FALSE(warned("envmap"));
    // At the horizon the two rows mix (+5); columns sit at u = 1/8, 3/8, ...
    EXPECT_NEAR(eval_background(s, {0, 1, 0}).x, 1.5f + 5, 1e-4f);   // the map's -z: u = 0
    EXPECT_NEAR(eval_background(s, {1, 0, 0}).x, 0.5f + 5, 1e-4f);   // its +x: u = 1/4
    EXPECT_NEAR(eval_background(s, {-1, 0, 0}).x, 2.5f + 5, 1e-4f);  // its -x: u = 3/4
    // Near its poles, world +z and -z, its top and bottom rows (at u = 1/4).
    EXPECT_NEAR(eval_background(s, {1e-3f, 0, 1}).x, 0.5f, 0.01f);
    EXPECT_NEAR(eval_background(s, {1e-3f, 0, -1}).x, 10.5f, 0.01f);
}

TEST(MitsubaScenes, MediaFillShapesThatNameThemInterior) {
    TempDir dir;
    // Mitsuba's participating_media tests declare a medium once and refer to it by name.
    auto path = dir.write("a.xml", scene(R"(
  <medium id="fog" type="homogeneous"><float name="scale" value="0.5"/>
    <rgb name="sigma_t" value="2, 1, 4"/><rgb name="albedo" value="0.9, 0.7, 0.9"/></medium>
  <shape type="sphere"><bsdf type="dielectric"/><ref id="fog" name="interior"/></shape>
  <shape type="sphere"><point name="center" x="3" y="0" z="0"/>
    <bsdf type="null"/><ref id="fog" name="interior"/></shape>)"));
    Scene s = load_scene(path, collecting());
    ASSERT_EQ(s.media.size(), 1u);  // one medium, named twice
    // sigma_t x scale, per channel
    EXPECT_NEAR(s.media[0].sigma_t.x, 1.0f, 1e-6f);
    EXPECT_NEAR(s.media[0].sigma_t.y, 0.5f, 1e-6f);
    EXPECT_NEAR(s.media[0].sigma_t.z, 2.0f, 1e-6f);
    ASSERT_EQ(s.spheres.size(), 2u);
    EXPECT_EQ(s.prim_interior(PrimRef::make(PrimKind::Sphere, 0)), 0u);
    EXPECT_EQ(s.prim_interior(PrimRef::make(PrimKind::Sphere, 1)), 0u);
    EXPECT_EQ(s.materials[s.spheres[0].material].kind, MaterialKind::Dielectric);
    EXPECT_TRUE(s.is_boundary(s.spheres[1].material));  // null BSDF: a boundary, no surface
    EXPECT_FALSE(warned("medium"));
    // Crossings follow Mitsuba's rule: the crossed shape's medium, not a nesting.
    EXPECT_EQ(s.medium_boundaries, MediumBoundaries::Interface);
}

TEST(MitsubaScenes, SpectraBecomeRgbAsMitsubasRgbVariantsSeeThem) {
    // tools/spectrum-to-rgb.py "400:0, 500:8, 600:15.6, 700:18.4" (the same computation in
    // Python) prints 20.690169 10.843802 2.768386.
    const Color rgb = spectrum_to_rgb({{400, 0}, {500, 8}, {600, 15.6}, {700, 18.4}}, false);
    EXPECT_NEAR(rgb.x, 20.690169f, 2e-5f);
    EXPECT_NEAR(rgb.y, 10.843802f, 2e-5f);
    EXPECT_NEAR(rgb.z, 2.768386f, 2e-5f);
    // A reflectance is clamped to [0, 1] per channel.
    const Color bounded = spectrum_to_rgb({{400, 0}, {500, 8}, {600, 15.6}, {700, 18.4}}, true);
    EXPECT_EQ(bounded.x, 1.0f);
    EXPECT_EQ(bounded.y, 1.0f);
    // A hotter black body is bluer.
    std::vector<std::pair<double, double>> cool, hot;
    for (int nm = 360; nm <= 830; nm += 5) {
        cool.emplace_back(nm, planck(nm, 3000));
        hot.emplace_back(nm, planck(nm, 9000));
    }
    const Color c = spectrum_to_rgb(cool, false), h = spectrum_to_rgb(hot, false);
    EXPECT_GT(c.x / c.z, h.x / h.z);
}

TEST(MitsubaScenes, ParametersComeFromDefaultsAndDefines) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(<default name="r" value="0.25"/>
  <shape type="sphere"><float name="radius" value="$r"/></shape>)"));
    EXPECT_NEAR(load_scene(path, collecting()).spheres[0].radius, 0.25f, 1e-7f);
    LoadOptions o = collecting();
    o.params["r"] = "3";
    EXPECT_NEAR(load_scene(path, o).spheres[0].radius, 3.0f, 1e-7f);

    auto undefined = dir.write("b.xml", scene(R"(<shape type="sphere">
  <float name="radius" value="$size"/></shape>)"));
    const std::string e = error_of(undefined);
    EXPECT_NE(e.find("b.xml:3"), std::string::npos) << e;
    EXPECT_NE(e.find("undefined parameter"), std::string::npos) << e;
}

TEST(MitsubaScenes, IncludesFindFilesThroughPathsAndCyclesAreRefused) {
    TempDir dir;
    dir.write("common/parts/ball.xml", scene(R"(<shape type="sphere"/>)"));
    auto main = dir.write("scenes/a/main.xml", scene(R"(<path value="../../common"/>
  <include filename="parts/ball.xml"/>)"));
    EXPECT_EQ(load_scene(main, collecting()).spheres.size(), 1u);

    dir.write("x.xml", scene(R"(<include filename="y.xml"/>)"));
    dir.write("y.xml", scene(R"(<include filename="x.xml"/>)"));
    const std::string e = error_of(dir.path() / "x.xml");
    EXPECT_NE(e.find("include cycle"), std::string::npos) << e;
    EXPECT_NE(e.find("y.xml:2"), std::string::npos) << e;
}

TEST(MitsubaScenes, VersionZeroSixFilesAreUpgradedAsMitsuba3Does) {
    TempDir dir;
    auto old_file = dir.write("old.xml", scene(R"(
  <integrator type="path"><integer name="maxDepth" value="3"/></integrator>
  <sensor type="perspective"><float name="fov" value="40"/><string name="fovAxis" value="y"/>
    <transform name="toWorld"><lookAt origin="0,0,5" target="0,0,0" up="0,1,0"/></transform>
    <sampler type="independent"><integer name="sampleCount" value="9"/></sampler></sensor>
  <shape type="sphere"><bsdf type="dielectric"><float name="intIOR" value="1.7"/>
    <float name="extIOR" value="1.0"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="3" y="0" z="0"/>
    <bsdf type="diffuse"><rgb name="diffuseReflectance" value="0.4"/></bsdf></shape>)",
                                               "0.6.0"));
    Scene s = load_scene(old_file, collecting());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    EXPECT_EQ(s.render.max_depth, 3);
    EXPECT_EQ(s.render.spp, 9);
    EXPECT_NEAR(s.camera.vfov, 40.0f, 1e-4f);
    EXPECT_NEAR(s.materials[s.spheres[0].material].ior, 1.7f, 1e-6f);
    EXPECT_NEAR(s.textures[s.materials[s.spheres[1].material].albedo].color.y, 0.4f, 1e-6f);
}

TEST(MitsubaScenes, BadInputNamesTheFileAndLine) {
    TempDir dir;
    struct Case {
        std::string body, expect;
    };
    const std::vector<Case> cases = {
        {"<shape type=\"sphere\">\n<float name=\"radius\" value=\"1.2.3\"/></shape>", "a.xml:3"},
        {"<shape type=\"sphere\">\n<ref id=\"nothing\"/></shape>", "no element with id"},
        {"<bsdf type=\"diffuse\" id=\"x\"/>\n<bsdf type=\"diffuse\" id=\"x\"/>", "duplicate id"},
        {"<shape type=\"sphere\"><bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"1 2\"/>"
         "</bsdf></shape>",
         "a.xml:3"},
        {"<shape type=\"sphere\">\n<transform name=\"to_world\"><shear/></transform></shape>",
         "a.xml:3"},
        {"<shape type=\"sphere\"><float name=\"radius\" value=\"1\">", "a.xml"},
        // A reflectance above 1, found by the JSON loader: the material names its element.
        {"<shape type=\"sphere\"><bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"2\"/>"
         "</bsdf></shape>",
         "diffuse at a.xml:2"},
        // ... and in a light: its element's line.
        {"\n<emitter type=\"spot\"><texture name=\"texture\" type=\"bitmap\">"
         "<string name=\"filename\" value=\"missing.png\"/></texture></emitter>",
         "a.xml:3: /lights/0/texture/file: cannot open image"},
    };
    for (const Case& c : cases) {
        auto path = dir.write("a.xml", scene(c.body));
        const std::string e = error_of(path, collecting());
        EXPECT_NE(e.find(c.expect), std::string::npos) << c.body << "\n -> " << e;
    }
    auto doctype = dir.write("d.xml", "<!DOCTYPE scene [<!ENTITY a \"aaaa\">]>\n" +
                                          scene("<shape type=\"sphere\"/>"));
    EXPECT_NE(error_of(doctype).find("DOCTYPE"), std::string::npos);
    auto versionless = dir.write("v.xml", "<scene><shape type=\"sphere\"/></scene>");
    EXPECT_NE(error_of(versionless).find("version"), std::string::npos);
}

TEST(MitsubaScenes, WhatCannotBeRepresentedIsAWarningWithItsPlace) {
    TempDir dir;
    auto path = dir.write("a.xml", scene(R"(<shape type="sphere"/>
  <shape type="bsplinecurve"><string name="filename" value="a.txt"/></shape>
  <shape type="sphere"><bsdf type="hair"/></shape>
  <shape type="sphere"><float name="wobble" value="1"/></shape>
  <shape type="disk"><bsdf type="diffuse"><texture name="reflectance" type="checkerboard"/></bsdf></shape>)"));
    Scene s = load_scene(path, collecting());
    EXPECT_EQ(s.spheres.size(), 3u);
    EXPECT_TRUE(warned("a.xml:6: warning: disk: its texture coordinates are wavetrace's, not Mitsuba's"));
    EXPECT_TRUE(warned("a.xml:3: warning: shape \"bsplinecurve\" is not supported"))
        << warnings.size();
    EXPECT_TRUE(warned("a.xml:4: warning: bsdf \"hair\""));
    EXPECT_TRUE(warned("a.xml:5: warning: shape \"sphere\": property \"wobble\""));
}

TEST(MitsubaScenes, ConvertWritesJsonThatRendersBitIdentically) {
    TempDir dir;
    const std::filesystem::path scenes =
        std::filesystem::path(WAVETRACE_REFERENCE_DIR) / "mitsuba3/tests/scenes";
    // Instances, and a heterogeneous medium whose grids the JSON names from another folder.
    for (const char* name : {"instancing/test_instancing_path.xml",
                             "participating_media/test_hetero_sigmat_albedo_volpath.xml"}) {
        const std::filesystem::path xml = scenes / name;
        const std::string json = (dir.path() / "out" / "scene.json").string();
        std::filesystem::create_directories(dir.path() / "out");
        CliResult c = run_cli(dir, "convert '" + xml.string() + "' -o '" + json + "'");
        ASSERT_EQ(c.code, 0) << c.err;
        // PFM: the pixels alone (an EXR's header names the scene file and the time).
        const std::string from_xml = (dir.path() / "xml.pfm").string();
        const std::string from_json = (dir.path() / "json.pfm").string();
        for (const auto& [scene_file, out] :
             {std::pair{xml.string(), from_xml}, {json, from_json}}) {
            CliResult r =
                run_cli(dir, "render '" + scene_file + "' --spp 4 --seed 3 -o '" + out + "'");
            ASSERT_EQ(r.code, 0) << r.err;
        }
        EXPECT_EQ(read(from_xml), read(from_json)) << name;
        const bool instancing = std::string(name).find("instancing") != std::string::npos;
        EXPECT_NE(read(json).find(instancing ? "\"group\"" : "\"density_grid\""),
                  std::string::npos);
    }
}

// A heterogeneous medium: the sigma_t volume's grid, placed by its to_world, bounds the medium
// (a constvolume's box too); what our grids do not do is an error with its place.
TEST(MitsubaScenes, HeterogeneousMediaMapTheirVolumes) {
    TempDir dir;
    std::string grid = "VOL";
    grid += char(3);
    for (int32_t v : {1, 2, 1, 1, 1}) grid.append(reinterpret_cast<const char*>(&v), 4);
    for (float v : {0.0f, 0.0f, 0.0f, 1.0f, 1.0f, 1.0f, 0.25f, 4.0f})
        grid.append(reinterpret_cast<const char*>(&v), 4);
    dir.write("g.vol", grid);
    grid.replace(grid.size() - 4, 4, std::string("\0\0\0\x3f", 4));  // 4 -> 0.5
    dir.write("a.vol", grid);
    auto medium = [&](const std::string& sigma_t, const std::string& albedo) {
        return dir.write("m.xml", scene(R"(<medium type="heterogeneous" id="m">
    <float name="scale" value="3"/>)" + sigma_t +
                                        albedo + R"(</medium>
  <shape type="sphere"><bsdf type="null"/><ref id="m" name="interior"/></shape>)"));
    };
    const std::string grid_volume = R"(<volume name="sigma_t" type="gridvolume">
      <string name="filename" value="g.vol"/>
      <transform name="to_world"><translate x="-0.5" y="-0.5" z="-0.5"/></transform>)";
    Scene s = load_scene(medium(grid_volume + "</volume>", R"(<rgb name="albedo" value="0.5"/>)"),
                         collecting());
    ASSERT_EQ(s.media.size(), 1u);
    ASSERT_TRUE(s.media[0].heterogeneous());
    EXPECT_EQ(s.media[0].sigma_t.x, 3.0f);
    const VolumeGrid& g = s.volume_grids[s.media[0].density_grid];
    EXPECT_NEAR(g.lookup({-0.25f, 0.0f, 0.0f}).x, 0.25f, 1e-6f);  // voxel 0's centre
    EXPECT_NEAR(g.lookup({0.25f, 0.0f, 0.0f}).x, 4.0f, 1e-6f);
    s = load_scene(medium(R"(<volume name="sigma_t" type="constvolume">
      <rgb name="value" value="0.5, 0.4, 0.3"/></volume>)",
                          R"(<volume name="albedo" type="gridvolume">
      <string name="filename" value="a.vol"/></volume>)"),
                   collecting());
    EXPECT_EQ(s.volume_grids[s.media[0].density_grid].channels, 3);
    const Texture& albedo = s.textures[s.materials[s.media[0].phase].albedo];
    EXPECT_EQ(albedo.kind, TextureKind::Grid);
    // An albedo grid above 1, and what our grids do not do: errors naming the file and line.
    EXPECT_NE(error_of(medium(R"(<float name="sigma_t" value="1"/>)",
                              R"(<volume name="albedo" type="gridvolume">
      <string name="filename" value="g.vol"/></volume>)"))
                  .find("must not exceed 1"),
              std::string::npos);
    EXPECT_NE(
        error_of(medium(grid_volume + R"(<string name="filter_type" value="cubic"/></volume>)", ""))
            .find("m.xml:3: gridvolume: filter_type \"cubic\""),
        std::string::npos);
    EXPECT_NE(
        error_of(medium(grid_volume + R"(<string name="wrap_mode" value="border"/></volume>)", ""))
            .find("wrap_mode \"border\""),
        std::string::npos);
    EXPECT_NE(error_of(medium(R"(<volume name="sigma_t" type="gridvolume"/>)", ""))
                  .find("needs a filename"),
              std::string::npos);
    // The file's box (x from 2 to 6 here), mapped onto the unit cube before to_world; the
    // filter and the wrap mode.
    std::string boxed = grid;
    const float box[6] = {2, 0, 0, 6, 1, 1};
    boxed.replace(24, 24, reinterpret_cast<const char*>(box), 24);
    dir.write("g.vol", boxed);
    s = load_scene(medium(grid_volume + R"(<boolean name="use_grid_bbox" value="true"/>
      <string name="filter_type" value="nearest"/><string name="wrap_mode" value="mirror"/>
      </volume>)",
                          ""),
                   collecting());
    const VolumeGrid& b = s.volume_grids[s.media[0].density_grid];
    EXPECT_TRUE(b.nearest);
    EXPECT_EQ(b.wrap, TextureWrap::Mirror);
    EXPECT_EQ(b.lookup({2.5f, 0.0f, 0.0f}).x, 0.25f);  // local x 3: the box's first half
    EXPECT_EQ(b.lookup({4.5f, 0.0f, 0.0f}).x, 0.5f);   // (a.vol's 0.5 written over the 4)
}

// Mitsuba gives a mesh whose file has no vertex normals smooth ones (unless face_normals): a
// pyramid's apex normal is the area-weighted mean of its four faces', straight up; a base
// corner's the mean of its two faces' (0, -2, 2) and (-2, 0, 2), z = sqrt(2/3).
TEST(MitsubaScenes, AMeshWithoutNormalsIsShadedSmoothAsInMitsuba) {
    TempDir dir;
    dir.write("pyramid.obj",
              "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nv 0 0 1\n"
              "f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n");
    for (const bool face_normals : {false, true}) {
        auto path = dir.write("a.xml", scene(std::string(R"(
  <shape type="obj"><string name="filename" value="pyramid.obj"/>
    <boolean name="face_normals" value=")") + (face_normals ? "true" : "false") +
                                             R"("/>
    <bsdf type="diffuse"/></shape>)"));
        Scene s = load_scene(path, collecting());
        ASSERT_EQ(s.meshes.size(), 1u);
        EXPECT_EQ(s.meshes[0].has_normals, !face_normals);
        if (face_normals) continue;
        for (size_t v = 0; v < s.positions.size(); ++v)
            if (s.positions[v].z > 0.5f) {
                EXPECT_NEAR(s.normals[v].z, 1.0f, 1e-6f);
            } else {
                EXPECT_NEAR(s.normals[v].z, std::sqrt(2.0f / 3.0f), 1e-5f);
            }
    }
}
