// pbrt-v4 scene files: each directive lands in the Scene where pbrt-v4's file format says it
// acts (camera, film, sampler, integrator, transforms, attributes, shapes, materials,
// textures, lights, media, instancing, includes), bad input names the file and line, what
// cannot be represented is a warning with its place, `convert` writes a JSON scene (and PLY
// meshes) that renders bit-identically, and Bitterli's Cornell box in pbrt's format renders
// the image Tungsten renders of it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"
#include "load_warnings.h"
#include "ramp_image.h"
#include "scene/delta_lights.h"
#include "temp_dir.h"
#include "wavetrace/wavetrace.h"

using namespace wavetrace;

namespace {


std::string error_of(const std::filesystem::path& path) {
    try {
        load_scene(path, collecting());
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

// A grid medium `name` of `type`, 2 x 1 x 1 samples over p0..p1 = [0 0 0]..[4 1 1] moved to
// x 10..14, with `params` on the directive's second line (line 7 of the file), filling a sphere.
std::filesystem::path grid_medium_scene(TempDir& dir,
                                        const std::string& name,
                                        const std::string& type,
                                        const std::string& params) {
    return dir.write("a.pbrt", R"(
Camera "perspective"
WorldBegin
AttributeBegin
  Translate 10 0 0
  MakeNamedMedium ")" + name + R"(" "string type" ")" +
                                   type +
                                   R"(" "integer nx" 2 "integer ny" 1 "integer nz" 1
    "point3 p0" [0 0 0] "point3 p1" [4 1 1] )" +
                                   params + R"(
AttributeEnd
AttributeBegin
  MediumInterface ")" + name + R"(" ""
  Material "interface"
  Shape "sphere" "float radius" 20
AttributeEnd
)");
}

std::string read(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

const Material& material_of_triangle(const Scene& s, size_t t) {
    return s.materials[s.meshes[s.triangles[t].mesh].material];
}

}  // namespace

TEST(PbrtScenes, CameraFilmSamplerAndIntegratorSetTheRender) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(# a comment
LookAt 1 2 3  1 2 10  0 1 0
Camera "perspective" "float fov" [ 30 ]
Film "rgb" "integer xresolution" [ 40 ] "integer yresolution" 80
  "string filename" "a.exr"
Sampler "halton" "integer pixelsamples" 7
Integrator "volpath" "integer maxdepth" [ 4 ]
WorldBegin
Shape "sphere"
)");
    Scene s = load_scene(path, collecting());
    EXPECT_EQ(s.render.width, 40);
    EXPECT_EQ(s.render.height, 80);
    EXPECT_EQ(s.render.spp, 7);
    // pbrt counts bounces, wavetrace path segments.
    EXPECT_EQ(s.render.max_depth, 5);
    EXPECT_NEAR(s.camera.look_from.x, 1.0f, 1e-6f);
    EXPECT_NEAR(s.camera.look_from.y, 2.0f, 1e-6f);
    EXPECT_NEAR(s.camera.look_from.z, 3.0f, 1e-6f);
    EXPECT_NEAR(s.camera.look_at.z, 4.0f, 1e-5f);
    // fov is the shorter side's: here the width's, so the height sees more.
    const double tan_v = std::tan(15.0 * 3.14159265358979 / 180) * 2;
    EXPECT_NEAR(s.camera.vfov, 2 * std::atan(tan_v) * 180 / 3.14159265358979, 1e-4);
    // pbrt's image right is camera +x = up x forward: our camera mirrored.
    EXPECT_TRUE(s.camera.mirror);
    EXPECT_TRUE(warned("a.pbrt:6: warning: Sampler \"halton\": wavetrace draws Owen-scrambled "
                       "Sobol points per pixel"));
    EXPECT_EQ(s.render.sampler, SamplerKind::Sobol);
}

// pbrt-v4's default sampler is zsobol, and ours stands for it; a named one is taken as it is.
TEST(PbrtScenes, ZSobolIsTheDefaultSampler) {
    TempDir dir;
    const std::string world = "WorldBegin\nShape \"sphere\"\n";
    EXPECT_EQ(load_scene(dir.write("a.pbrt", world)).render.sampler, SamplerKind::ZSobol);
    EXPECT_EQ(load_scene(dir.write("b.pbrt", "Sampler \"zsobol\"\n" + world)).render.sampler,
              SamplerKind::ZSobol);
    EXPECT_EQ(load_scene(dir.write("c.pbrt", "Sampler \"independent\"\n" + world)).render.sampler,
              SamplerKind::Independent);
}

// pbrt's camera puts camera-space +x on the image's right: a red sphere at +x, seen from the
// origin looking down +z, is in the right half of the image, as pbrt renders it.
TEST(PbrtScenes, TheImageIsNotMirrored) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(
Camera "perspective" "float fov" 60
Film "rgb" "integer xresolution" 32 "integer yresolution" 16
WorldBegin
LightSource "infinite" "rgb L" [1 1 1]
AttributeBegin
  Material "diffuse" "rgb reflectance" [0.8 0 0]
  Translate 2 0 8
  Shape "sphere" "float radius" 1
AttributeEnd
)");
    Scene s = load_scene(path, collecting());
    Bvh bvh = Bvh::build(s);
    RenderRequest r;
    r.width = 32;
    r.height = 16;
    r.spp = 4;
    Film film(r.width, r.height);
    render(s, bvh, r, film);
    const Image img = film.mean();
    double left = 0, right = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 32; ++x) {
            const Color c = img.at(x, y);
            // The sphere is red; the sky white.
            const double red = c.x - c.y;
            (x < 16 ? left : right) += red;
        }
    EXPECT_GT(right, 10 * std::max(left, 1e-3));
}

TEST(PbrtScenes, ShapesTransformsMaterialsAndInstancesTranslate) {
    TempDir dir;
    dir.write("inc/part.pbrt", R"(Shape "sphere" "float radius" 0.5)");
    auto path = dir.write("a.pbrt", R"(
LookAt 0 0 -10  0 0 0  0 1 0
Camera "perspective"
WorldBegin
MakeNamedMaterial "gold" "string type" "conductor"
  "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k" "float roughness" 0.04
MakeNamedMaterial "glass" "string type" "dielectric" "spectrum eta" "glass-BK7"
Texture "checks" "spectrum" "checkerboard" "float uscale" 4 "float vscale" 4
  "rgb tex1" [1 0 0] "rgb tex2" [0 0 1]
AttributeBegin
  NamedMaterial "gold"
  Translate 3 0 0
  Scale 2 2 2
  Shape "sphere" "float radius" 1
AttributeEnd
AttributeBegin
  Material "coateddiffuse" "rgb reflectance" [0.4 0.2 0.2] "float roughness" 0.01
  Shape "bilinearmesh" "point3 P" [0 0 0  1 0 0  0 1 0  1 1 0]
AttributeEnd
AttributeBegin
  Material "diffuse" "texture reflectance" "checks"
  Shape "trianglemesh" "point3 P" [0 0 0 1 0 0 1 1 0] "point2 uv" [0 0 1 0 1 1]
    "normal N" [0 0 -1 0 0 -1 0 0 -1]
AttributeEnd
AttributeBegin
  NamedMaterial "glass"
  Translate 0 5 0
  AreaLightSource "diffuse" "rgb L" [4 4 4] "bool twosided" true
  Shape "disk" "float radius" 2
AttributeEnd
ObjectBegin "pair"
  Include "inc/part.pbrt"
  Translate 0 0 2
  Include "inc/part.pbrt"
ObjectEnd
AttributeBegin
  Translate -4 0 0
  ObjectInstance "pair"
  Translate 0 -3 0
  ObjectInstance "pair"
AttributeEnd
)");
    Scene s = load_scene(path, collecting());
    // The gold sphere (radius 1 scaled by 2 at x = 3) and four instanced ones.
    ASSERT_EQ(s.spheres.size(), 5u);
    EXPECT_NEAR(s.spheres[0].center.x, 3.0f, 1e-5f);
    EXPECT_NEAR(s.spheres[0].radius, 2.0f, 1e-5f);
    const Material& gold = s.materials[s.spheres[0].material];
    EXPECT_EQ(gold.kind, MaterialKind::Conductor);
    EXPECT_NEAR(gold.alpha_u, 0.2f, 1e-6f);  // remapped: sqrt(0.04)
    std::multiset<std::pair<float, float>> instanced;
    for (size_t i = 1; i < 5; ++i) {
        EXPECT_NEAR(s.spheres[i].radius, 0.5f, 1e-6f);
        instanced.insert({s.spheres[i].center.y, s.spheres[i].center.z});
        EXPECT_NEAR(s.spheres[i].center.x, -4.0f, 1e-5f);
    }
    EXPECT_EQ(instanced, (std::multiset<std::pair<float, float>>{{0, 0}, {0, 2}, {-3, 0}, {-3, 2}}));
    // Bilinear patch: 2 triangles; triangle: 1; disk: 128.
    EXPECT_EQ(s.triangles.size(), 2u + 1u + 128u);
    EXPECT_EQ(material_of_triangle(s, 0).kind, MaterialKind::Plastic);
    const Material& checks = material_of_triangle(s, 2);
    EXPECT_EQ(checks.kind, MaterialKind::Lambertian);
    // N points down -z: pbrt orients the surface by it, so the triangle was turned over.
    const Triangle& t = s.triangles[2];
    const Vec3 n = cross(s.positions[t.v[1]] - s.positions[t.v[0]],
                         s.positions[t.v[2]] - s.positions[t.v[0]]);
    EXPECT_LT(n.z, 0.0f);
    // The disk emits, reflecting nothing (its glass is not a diffuse surface: a warning).
    const Material& lamp = material_of_triangle(s, 3);
    EXPECT_EQ(lamp.kind, MaterialKind::DiffuseLight);
    EXPECT_TRUE(lamp.two_sided);
    EXPECT_TRUE(warned("an area light's surface reflects only as a diffuse surface"));
}

// Shape "cylinder": its side from zmin to zmax (pbrt's defaults -1 and 1), facing outwards,
// inwards under ReverseOrientation, its shading normals turned with it.
TEST(PbrtScenes, CylindersFaceOutwardsUnlessReversed) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(
LookAt 0 0 -10  0 0 0  0 1 0
Camera "perspective"
WorldBegin
Material "diffuse"
Shape "cylinder" "float radius" 2
AttributeBegin
  Translate 10 0 0
  ReverseOrientation
  Shape "cylinder" "float zmin" 0 "float zmax" 3
AttributeEnd
)");
    Scene s = load_scene(path, collecting());
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.triangles.size(), 2u * 256u);
    for (const Triangle& t : s.triangles) {
        const Vec3 a = s.positions[t.v[0]], b = s.positions[t.v[1]], c = s.positions[t.v[2]];
        const Vec3 m = (a + b + c) / 3.0f;
        const Vec3 out = t.mesh == 0 ? Vec3{m.x, m.y, 0} : Vec3{m.x - 10, m.y, 0};
        const float facing = dot(cross(b - a, c - a), out);
        const float shading = dot(s.normals[t.v[0]], out);
        if (t.mesh == 0) {
            EXPECT_GT(facing, 0.0f);
            EXPECT_GT(shading, 0.0f);
            EXPECT_GE(m.z, -1.0f);
            EXPECT_LE(m.z, 1.0f);
        } else {
            EXPECT_LT(facing, 0.0f);
            EXPECT_LT(shading, 0.0f);
            EXPECT_GE(m.z, 0.0f);
            EXPECT_LE(m.z, 3.0f);
        }
    }
}

TEST(PbrtScenes, LightsBecomeLightsAndBackgrounds) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(
LookAt 0 0 0  0 0 1  0 1 0
Camera "perspective"
WorldBegin
LightSource "point" "rgb I" [1 2 3] "point3 from" [0 1 0] "float scale" 2
AttributeBegin
  Translate 0 0 5
  LightSource "spot" "blackbody I" 3000 "float coneangle" 40 "float conedelta" 10
AttributeEnd
AttributeBegin
  CoordSysTransform "camera"
  LightSource "distant" "rgb L" [0.5 0.5 0.5]
AttributeEnd
LightSource "infinite" "rgb L" [0.1 0.2 0.3]
Shape "sphere"
)");
    Scene s = load_scene(path, collecting());
    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Point);
    EXPECT_NEAR(s.lights[0].position.y, 1.0f, 1e-6f);
    EXPECT_NEAR(s.lights[0].intensity.z, 6.0f, 1e-5f);
    EXPECT_EQ(s.lights[1].kind, Light::Kind::Spot);
    EXPECT_NEAR(s.lights[1].position.z, 5.0f, 1e-5f);
    EXPECT_NEAR(s.lights[1].cutoff_degrees, 40.0f, 1e-5f);
    EXPECT_NEAR(s.lights[1].falloff_start_degrees, 30.0f, 1e-5f);
    // A black body is of unit luminance in pbrt; 3000 K is reddish.
    const Color bb = s.lights[1].intensity;
    EXPECT_NEAR(luminance(bb), 1.0f, 1e-3f);
    EXPECT_GT(bb.x, bb.z);
    // The camera's frame: the light travels along the view (+z).
    EXPECT_EQ(s.lights[2].kind, Light::Kind::Directional);
    EXPECT_NEAR(s.lights[2].direction.z, 1.0f, 1e-5f);
    EXPECT_EQ(s.background.kind, Background::Kind::Constant);
    EXPECT_NEAR(s.background.radiance.y, 0.2f, 1e-6f);
}

// pbrt-v4's projection light: its image's nearest texel times scale is the intensity itself
// (no 1/cos^3 as Mitsuba's projector has), through a frustum of `fov` on the image's shorter
// side, the image upright towards the light's +y and its right towards +x (pbrt flips the
// light's y): four coloured quadrants, and a 2 x 1 ramp (texels 0 and 1, left to right).
TEST(PbrtScenes, ProjectionLightsProjectIntensityUpright) {
    TempDir dir;
    Image img(2, 2);
    img.at(0, 0) = Color(1, 0, 0);  // top left
    img.at(1, 0) = Color(0, 1, 0);  // top right
    img.at(0, 1) = Color(0, 0, 1);  // bottom left
    img.at(1, 1) = Color(1, 1, 1);
    write_image(dir.path() / "quads.exr", img);
    write_image(dir.path() / "wide.exr", ramp_image(2, 1));
    auto path = dir.write("a.pbrt", R"(Camera "perspective"
WorldBegin
LightSource "projection" "string filename" "quads.exr" "float fov" 60 "float scale" 3
LightSource "projection" "string filename" "wide.exr" "float fov" 40
Shape "sphere"
)");
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
    ASSERT_EQ(s.lights.size(), 2u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.kind, Light::Kind::Projector);
    EXPECT_TRUE(l.projects_intensity);
    const float t = std::tan(30.0f * 3.14159265f / 180.0f);
    EXPECT_NEAR(l.half_width, t, 1e-5f);
    EXPECT_NEAR(l.half_height, t, 1e-5f);
    auto at = [&](const Light& x, float sx, float sy) {  // towards screen point (sx, sy)
        return delta_light_intensity(s, x, normalize(Vec3(sx, sy, 1.0f)));
    };
    const Color tl = at(l, -0.5f * t, 0.5f * t), tr = at(l, 0.5f * t, 0.5f * t),
                bl = at(l, -0.5f * t, -0.5f * t);
    EXPECT_NEAR(tl.x, 3.0f, 1e-5f);
    EXPECT_NEAR(tl.y + tl.z, 0.0f, 1e-6f);
    EXPECT_NEAR(tr.y, 3.0f, 1e-5f);
    EXPECT_NEAR(tr.x + tr.z, 0.0f, 1e-6f);
    EXPECT_NEAR(bl.z, 3.0f, 1e-5f);
    EXPECT_EQ(max_component(at(l, 1.1f * t, 0.0f)), 0.0f);  // outside the frustum
    // The 2:1 image: the field of view on its shorter (vertical) side.
    const Light& w = s.lights[1];
    const float u = std::tan(20.0f * 3.14159265f / 180.0f);
    EXPECT_NEAR(w.half_height, u, 1e-5f);
    EXPECT_NEAR(w.half_width, 2 * u, 1e-5f);
    EXPECT_NEAR(at(w, -u, 0.0f).x, 0.0f, 1e-6f);
    EXPECT_NEAR(at(w, u, 0.0f).x, 1.0f, 1e-6f);
}

// pbrt-v4's image infinite light: a square equal-area map in the light's frame (here turned
// by the usual `Rotate -90 1 0 0`, its +z to world +y), each direction at its nearest texel;
// a map that is not square is refused as pbrt-v4 refuses it, naming the file and line.
TEST(PbrtScenes, InfiniteLightImagesAreEqualAreaMapsInTheLightsFrame) {
    TempDir dir;
    const Image env = ramp_image(4, 4);
    write_image(dir.path() / "sky.exr", env);
    write_image(dir.path() / "wide.exr", Image(8, 4));
    const std::string head = "Camera \"perspective\"\nWorldBegin\nAttributeBegin\n"
                             "Rotate -90 1 0 0\n";
    auto path = dir.write("a.pbrt", head + "LightSource \"infinite\" \"string filename\" "
                                           "\"sky.exr\" \"float scale\" 2\nAttributeEnd\n");
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
    ASSERT_EQ(s.background.kind, Background::Kind::Environment);
    EXPECT_EQ(s.background.mapping, Background::Mapping::EqualArea);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            // pbrt-v4's EqualAreaSquareToSphere at the texel's centre, in the light's frame.
            const float a = 2 * (x + 0.5f) / 4 - 1, b = 2 * (y + 0.5f) / 4 - 1;
            const float r = 1 - std::abs(1 - std::abs(a) - std::abs(b));
            const float phi = ((std::abs(b) - std::abs(a)) / r + 1) * 3.14159265f / 4;
            const float z = std::copysign(1 - r * r, 1 - std::abs(a) - std::abs(b));
            const float planar = r * std::sqrt(2 - r * r);
            const Vec3 l(std::copysign(std::cos(phi), a) * planar,
                         std::copysign(std::sin(phi), b) * planar, z);
            EXPECT_EQ(eval_background(s, {l.x, l.z, -l.y}).x, 2.0f * (x + 10 * y)) << x << y;
        }
    // `illuminance` as pbrt-v4 applies it: scale E_v / k_e, k_e the sum over the texels whose
    // centre lies above the map's horizon of Y cos(theta), times 2 pi / N.
    path = dir.write("i.pbrt", head + "LightSource \"infinite\" \"string filename\" "
                                      "\"sky.exr\" \"float illuminance\" 3\nAttributeEnd\n");
    s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
    double k_e = 0;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const float a = 2 * (x + 0.5f) / 4 - 1, b = 2 * (y + 0.5f) / 4 - 1;
            const float r = 1 - std::abs(1 - std::abs(a) - std::abs(b));
            const float z = std::copysign(1 - r * r, 1 - std::abs(a) - std::abs(b));
            if (z > 0) k_e += (x + 10 * y) * z;  // a grey texel's luminance is its value
        }
    k_e *= 2 * 3.14159265 / 16;
    EXPECT_NEAR(s.background.radiance.x, 3 / k_e, 1e-5 * 3 / k_e);
    auto wide = dir.write("b.pbrt", head + "LightSource \"infinite\" \"string filename\" "
                                           "\"wide.exr\"\nAttributeEnd\n");
    const std::string e = error_of(wide);
    EXPECT_NE(e.find("b.pbrt:5: "), std::string::npos) << e;
    EXPECT_NE(e.find("an equal_area map must be square; '"), std::string::npos) << e;
    EXPECT_NE(e.find("wide.exr' is 8 x 4"), std::string::npos) << e;
}

// An imagemap's filter "point" is the nearest texel and its wrap "clamp" ours; pbrt-v4's
// mip-mapped filters are bilinear here, with a warning.
TEST(PbrtScenes, ImagemapFiltersAndWrapsAreKept) {
    TempDir dir;
    write_image(dir.path() / "t.exr", ramp_image(4, 4));
    auto path = dir.write("a.pbrt", R"(Camera "perspective"
WorldBegin
Texture "a" "spectrum" "imagemap" "string filename" "t.exr" "string filter" "point"
  "string wrap" "clamp"
Texture "b" "spectrum" "imagemap" "string filename" "t.exr" "string filter" "ewa"
Texture "c" "spectrum" "imagemap" "string filename" "t.exr" "string wrap" "black"
Material "diffuse" "texture reflectance" "a"
Shape "sphere"
Material "diffuse" "texture reflectance" "b"
Shape "sphere"
Material "diffuse" "texture reflectance" "c"
Shape "sphere"
)");
    Scene s = load_scene(path, collecting());
    std::vector<std::pair<TextureFilter, TextureWrap>> images;
    for (const Texture& t : s.textures)
        if (t.kind == TextureKind::Image) {
            images.emplace_back(t.filter, t.wrap_u);
            EXPECT_EQ(t.wrap_v, t.wrap_u);
        }
    std::vector<std::pair<TextureFilter, TextureWrap>> expected = {
        {TextureFilter::Nearest, TextureWrap::Clamp},
        {TextureFilter::Bilinear, TextureWrap::Repeat},
        {TextureFilter::Bilinear, TextureWrap::Black}};
    std::sort(images.begin(), images.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(images, expected);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("filter \"ewa\" is not supported; bilinear is used"),
              std::string::npos)
        << warnings[0];
}

// A sphere's texture coordinates are pbrt-v4's, in the frame of its CTM: u = phi / 2 pi about
// its +z from +x, v = 1 - theta / pi; pbrt-v4's image textures read row (1 - v) H from the top.
// Here `Rotate 90 1 0 0` turns its +z to world -y; texel (i, j) holds i + 10 j.
TEST(PbrtScenes, SphereTexturesFollowPbrtsMappingInItsFrame) {
    TempDir dir;
    const Image img = ramp_image(4, 4);
    write_image(dir.path() / "t.exr", img);
    auto path = dir.write("a.pbrt", R"(Camera "perspective"
WorldBegin
Texture "t" "spectrum" "imagemap" "string filename" "t.exr"
Material "diffuse" "texture reflectance" "t"
AttributeBegin
  Rotate 90 1 0 0
  Shape "sphere"
AttributeEnd
)");
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
    EXPECT_FALSE(s.geometric_side_test);  // pbrt-v4's BSDFs answer in the shading frame
    const Bvh bvh = Bvh::build(s);
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const float u = (i + 0.5f) / 4, theta = 3.14159265f * (j + 0.5f) / 4;
            const float phi = 2 * 3.14159265f * u;
            const Vec3 local{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                             std::cos(theta)};
            const Vec3 n{local.x, -local.z, local.y};
            const Ray ray{2.0f * n, -n};
            const Hit hit = bvh.intersect(ray);
            ASSERT_TRUE(hit.found());
            const SurfaceHit h = surface_at(s, ray, hit);
            EXPECT_NEAR(eval_texture(s, s.materials[h.material].albedo, h.uv, h.p).x, i + 10.0f * j,
                        1e-3f) << i << j;
        }
}

// pbrt-v4's uroughness and vroughness, remapped (alpha = sqrt(roughness)), become a conductor's
// alpha_u and alpha_v; equal ones its alpha.
TEST(PbrtScenes, ConductorRoughnessMayBeAnisotropic) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(Camera "perspective"
WorldBegin
Material "conductor" "float uroughness" 0.09 "float vroughness" 0.01
Shape "sphere"
Material "conductor" "float uroughness" 0.04 "float vroughness" 0.04
Shape "sphere"
)");
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
    ASSERT_EQ(s.spheres.size(), 2u);
    const Material& brushed = s.materials[s.spheres[0].material];
    EXPECT_NEAR(brushed.alpha_u, 0.3f, 1e-6f);
    EXPECT_NEAR(brushed.alpha_v, 0.1f, 1e-6f);
    const Material& even = s.materials[s.spheres[1].material];
    EXPECT_NEAR(even.alpha_u, 0.2f, 1e-6f);
    EXPECT_EQ(even.alpha_u, even.alpha_v);
}

// pbrt-v4's mix is our blend of its two named materials, "amount" its weight (a number,
// clamped to [0, 1], or a float texture); a material that has no surface is refused.
TEST(PbrtScenes, MixIsABlendOfTwoNamedMaterials) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(Camera "perspective"
WorldBegin
MakeNamedMaterial "red" "string type" "diffuse" "rgb reflectance" [0.8 0.1 0.1]
MakeNamedMaterial "gold" "string type" "conductor" "spectrum eta" "metal-Au-eta" "spectrum k" "metal-Au-k"
Texture "cells" "float" "checkerboard" "float uscale" 4 "float vscale" 4
Material "mix" "string materials" ["red" "gold"] "float amount" 0.3
Shape "sphere"
Material "mix" "string materials" ["gold" "red"] "texture amount" "cells"
Shape "sphere"
Material "mix" "string materials" ["gold" "red"] "float amount" 7
Shape "sphere"
)");
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
    ASSERT_EQ(s.spheres.size(), 3u);
    const Material& a = s.materials[s.spheres[0].material];
    ASSERT_EQ(a.kind, MaterialKind::Blend);
    EXPECT_EQ(s.materials[a.blend[0]].kind, MaterialKind::Lambertian);
    EXPECT_EQ(s.materials[a.blend[1]].kind, MaterialKind::Conductor);
    EXPECT_FLOAT_EQ(a.blend_weight.value, 0.3f);
    const Material& b = s.materials[s.spheres[1].material];
    ASSERT_EQ(b.kind, MaterialKind::Blend);
    EXPECT_EQ(s.materials[b.blend[0]].kind, MaterialKind::Conductor);
    EXPECT_NE(b.blend_weight.texture, kNone);
    EXPECT_FLOAT_EQ(s.materials[s.spheres[2].material].blend_weight.value, 1.0f);
    auto none = dir.write("n.pbrt", R"(Camera "perspective"
WorldBegin
MakeNamedMaterial "red" "string type" "diffuse"
MakeNamedMaterial "nothing" "string type" "interface"
Material "mix" "string materials" ["red" "nothing"]
Shape "sphere"
)");
    EXPECT_NE(error_of(none).find("n.pbrt:5"), std::string::npos) << error_of(none);
}

TEST(PbrtScenes, MediaFillShapesWithTheInterfaceMaterial) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(
Camera "perspective"
WorldBegin
MakeNamedMedium "fog" "string type" "homogeneous"
  "rgb sigma_a" [0.1 0.3 0.1] "rgb sigma_s" [0.9 0.9 0.9] "float scale" 2
AttributeBegin
  MediumInterface "fog" ""
  Material "interface"
  Translate 0 0 5
  Shape "sphere"
AttributeEnd
)");
    Scene s = load_scene(path, collecting());
    ASSERT_EQ(s.media.size(), 1u);
    // (sigma_a + sigma_s) x scale, per channel
    EXPECT_NEAR(s.media[0].sigma_t.x, 2.0f, 1e-6f);
    EXPECT_NEAR(s.media[0].sigma_t.y, 2.4f, 1e-6f);
    ASSERT_EQ(s.spheres.size(), 1u);
    EXPECT_EQ(s.spheres[0].interior, MediumId{0});
    EXPECT_TRUE(s.is_boundary(s.spheres[0].material));
}

// A uniformgrid medium: its density samples over p0..p1 in the medium's space, trilinear
// between them and 0 half a sample beyond the outermost (pbrt-v4's SampledGrid).
TEST(PbrtScenes, UniformGridMediaAreDensityGrids) {
    TempDir dir;
    auto scene = [&](const std::string& density) {
        return grid_medium_scene(
            dir, "smoke", "uniformgrid",
            "\"float density\" " + density +
                R"( "rgb sigma_a" [1 1 1] "rgb sigma_s" [3 3 3] "float scale" 0.5)");
    };
    Scene s = load_scene(scene("[2 6]"), collecting());
    ASSERT_EQ(s.media.size(), 1u);
    ASSERT_TRUE(s.media[0].heterogeneous());
    EXPECT_NEAR(s.media[0].sigma_t.x, 2.0f, 1e-6f);  // (1 + 3) x 0.5
    EXPECT_NEAR(s.textures[s.materials[s.media[0].phase].albedo].color.x, 0.75f, 1e-6f);  // 3 / 4
    const VolumeGrid& g = s.volume_grids[s.media[0].density_grid];
    EXPECT_EQ(g.wrap, TextureWrap::Black);
    // Samples at x 11 and 13 (the box 10..14): 2 and 6, 4 halfway, 1 at the box's face.
    EXPECT_NEAR(g.lookup({11.0f, 0.5f, 0.5f}).x, 2.0f, 1e-5f);
    EXPECT_NEAR(g.lookup({12.0f, 0.5f, 0.5f}).x, 4.0f, 1e-5f);
    EXPECT_NEAR(g.lookup({10.0f, 0.5f, 0.5f}).x, 1.0f, 1e-5f);
    EXPECT_NE(error_of(scene("[2 6 7]"))
                  .find("a.pbrt:6: medium \"smoke\": density needs nx ny nz = 2 values, got 3"),
              std::string::npos)
        << error_of(scene("[2 6 7]"));
}

// An rgbgrid medium: (sigma_a + sigma_s) x scale per channel as a three-channel density grid,
// sigma_s / sigma_t as a grid texture for the albedo, over the same box; a coefficient left out
// is 1 (pbrt-v4's RGBGridMedium).
TEST(PbrtScenes, RgbGridMediaAreThreeChannelGrids) {
    TempDir dir;
    auto scene = [&](const std::string& coefficients) {
        return grid_medium_scene(dir, "dye", "rgbgrid", "\"float scale\" 0.5 " + coefficients);
    };
    Scene s = load_scene(
        scene(R"("rgb sigma_a" [1 2 3  0.5 0.5 0.5] "rgb sigma_s" [3 2 1  1.5 1.5 1.5])"),
        collecting());
    ASSERT_EQ(s.media.size(), 1u);
    ASSERT_TRUE(s.media[0].heterogeneous());
    const VolumeGrid& g = s.volume_grids[s.media[0].density_grid];
    EXPECT_EQ(g.channels, 3);
    EXPECT_EQ(g.wrap, TextureWrap::Black);
    const Color near = s.media[0].sigma_t * g.lookup({11.0f, 0.5f, 0.5f});
    const Color far = s.media[0].sigma_t * g.lookup({13.0f, 0.5f, 0.5f});
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(near[c], 2.0f, 1e-5f) << c;  // (sigma_a + sigma_s) x 0.5
        EXPECT_NEAR(far[c], 1.0f, 1e-5f) << c;
    }
    const TextureId albedo = s.materials[s.media[0].phase].albedo;
    ASSERT_EQ(s.textures[albedo].kind, TextureKind::Grid);
    const Color a = eval_texture(s, albedo, {0.0f, 0.0f}, {11.0f, 0.5f, 0.5f});
    EXPECT_NEAR(a.x, 0.75f, 1e-5f);
    EXPECT_NEAR(a.y, 0.5f, 1e-5f);
    EXPECT_NEAR(a.z, 0.25f, 1e-5f);
    // sigma_a left out is 1: (1 + 3) x 0.5 in the first sample's red.
    Scene only_s = load_scene(scene(R"("rgb sigma_s" [3 2 1  1.5 1.5 1.5])"), collecting());
    EXPECT_NEAR((only_s.media[0].sigma_t *
                 only_s.volume_grids[only_s.media[0].density_grid].lookup({11.0f, 0.5f, 0.5f}))
                    .x,
                2.0f, 1e-5f);
    EXPECT_NE(error_of(scene(R"("rgb sigma_a" [1 2 3])"))
                  .find("a.pbrt:7: medium \"dye\": sigma_a needs 3 nx ny nz = 6 values, got 3"),
              std::string::npos)
        << error_of(scene(R"("rgb sigma_a" [1 2 3])"));
    EXPECT_NE(error_of(scene("")).find("an rgbgrid needs sigma_a or sigma_s"), std::string::npos);
}

// Loop subdivision of an octahedron: every level quadruples the faces, the mesh stays closed
// (each edge shared by two triangles), and the limit surface lies within the control hull
// and, by the octahedron's symmetry, keeps its six tips on the axes.
TEST(PbrtScenes, LoopSubdivisionRefinesAClosedMeshTowardsItsLimit) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(
Camera "perspective"
WorldBegin
Translate 0 0 5
Shape "loopsubdiv" "integer levels" 2
  "point3 P" [1 0 0  -1 0 0  0 1 0  0 -1 0  0 0 1  0 0 -1]
  "integer indices" [0 2 4  2 1 4  1 3 4  3 0 4  2 0 5  1 2 5  3 1 5  0 3 5]
)");
    Scene s = load_scene(path, collecting());
    ASSERT_EQ(s.triangles.size(), 8u * 16u);
    std::map<std::pair<uint32_t, uint32_t>, int> edges;
    for (const Triangle& t : s.triangles)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = t.v[e], b = t.v[(e + 1) % 3];
            ++edges[{std::min(a, b), std::max(a, b)}];
        }
    for (const auto& [edge, count] : edges) EXPECT_EQ(count, 2);
    float tip = 0;
    for (const Point3& p : s.positions) {
        const Vec3 q = p - Point3(0, 0, 5);
        EXPECT_LE(std::abs(q.x) + std::abs(q.y) + std::abs(q.z), 1.0f + 1e-5f);  // in the hull
        if (std::abs(q.y) < 1e-6f && std::abs(q.z) < 1e-6f) tip = std::max(tip, q.x);
    }
    EXPECT_GT(tip, 0.3f);
    EXPECT_LT(tip, 1.0f);
}

TEST(PbrtScenes, BadInputNamesTheFileAndLine) {
    TempDir dir;
    const std::string head = "Camera \"perspective\"\nWorldBegin\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"Shape \"sphere\" \"float radius\" [ 1", "a.pbrt:3: Shape \"sphere\": unclosed ["},
        {"Shape \"sphere\n", "a.pbrt:3: unterminated string"},
        {"Frobnicate 1 2", "a.pbrt:3: unknown directive Frobnicate"},
        {"Translate 1 2", "a.pbrt:3: Translate needs 3 numbers"},
        {"Translate 1 x 2", "a.pbrt:3: Translate: expected a number, got x"},
        {"Scale 1e99 1 1", "a.pbrt:3: number 1e99 is not finite in float"},
        {"AttributeEnd", "a.pbrt:3: AttributeEnd without a matching begin"},
        {"AttributeBegin\nTransformEnd", "a.pbrt:4: TransformEnd closes an AttributeBegin"},
        {"ObjectBegin \"o\"\nAttributeEnd\nObjectEnd", "a.pbrt:4: AttributeEnd without a matching begin"},
        {"ObjectBegin \"o\"\nAttributeBegin\nObjectEnd", "a.pbrt:5: ObjectEnd inside an AttributeBegin"},
        {"ObjectBegin \"o\"\nShape \"sphere\"", "a.pbrt:3: ObjectBegin without ObjectEnd"},
        {"NamedMaterial \"nope\"", "a.pbrt:3: no material named \"nope\""},
        {"ObjectInstance \"nope\"", "a.pbrt:3: no object named \"nope\""},
        {"Shape \"sphere\" \"flaot radius\" 1", "a.pbrt:3: Shape \"sphere\": unknown parameter type \"flaot\""},
        {"Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0 0 1 0] \"integer indices\" [0 1 3]",
         "a.pbrt:3: Shape \"trianglemesh\": index 3.000000 is not a point of \"P\" (0 .. 2)"},
        {"Shape \"trianglemesh\" \"point3 P\" [0 0 0 1 0 0]", "\"P\" with 3 or more points"},
        {"Include \"a.pbrt\"", "a.pbrt:3: Include \"a.pbrt\" includes itself"},
        {"Include \"missing.pbrt\"", "a.pbrt:3: cannot open"},
        {"Shape \"sphere\" \"float radius\" -1", "a.pbrt:3: Shape sphere: radius must be > 0"},
        {"Texture \"t\" \"color\" \"imagemap\"", "the kind is \"float\" or \"spectrum\""},
        {"Material \"diffuse\" \"texture reflectance\" \"nope\"", "a.pbrt:3: no texture named \"nope\""},
        // Found by the JSON loader in a light: the directive's line.
        {"\nLightSource \"projection\" \"string filename\" \"missing.png\"",
         "a.pbrt:4: /lights/0/intensity/file: cannot open image"},
        {"LightSource \"point\" \"float scale\" -1", "a.pbrt:3: /lights/0/intensity"},
    };
    for (const auto& [line, expected] : cases) {
        auto path = dir.write("a.pbrt", head + line + "\n");
        const std::string e = error_of(path);
        EXPECT_NE(e.find(expected), std::string::npos) << line << "\n -> " << e;
    }
    // A NUL byte: the file is not text.
    auto nul = dir.write("b.pbrt", head + std::string("Shape \"sphere\"\0", 15) + "\n");
    EXPECT_NE(error_of(nul).find("b.pbrt:3: a NUL byte"), std::string::npos) << error_of(nul);
    // The JSON loader's own checks name the directive's line.
    auto far = dir.write("c.pbrt", head + "Translate 1e8 0 0\nShape \"sphere\"\n");
    EXPECT_NE(error_of(far).find("c.pbrt:4: "), std::string::npos) << error_of(far);
}

TEST(PbrtScenes, WhatCannotBeRepresentedIsAWarningWithItsPlace) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(Camera "perspective" "float lensradius" 0.1
PixelFilter "mitchell"
WorldBegin
Shape "curve" "point3 P" [0 0 0 1 1 1 2 2 2 3 3 3]
Material "hair"
Shape "sphere" "float radius" 1 "float wobble" 3 "float zmax" 0.5
)");
    Scene s = load_scene(path, collecting());
    EXPECT_EQ(s.spheres.size(), 1u);
    EXPECT_NEAR(s.camera.aperture, 0.2f, 1e-6f);
    EXPECT_TRUE(warned("a.pbrt:2: warning: PixelFilter \"mitchell\" is not supported"));
    EXPECT_TRUE(warned("a.pbrt:4: warning: Shape \"curve\" is not supported; skipped"));
    EXPECT_TRUE(warned("a.pbrt:5: warning: Material \"hair\": material \"hair\" is not supported"));
    EXPECT_TRUE(warned("a.pbrt:6: warning: Shape \"sphere\": parameter \"wobble\" is not supported"));
    EXPECT_TRUE(warned("a.pbrt:6: warning: Shape sphere: partial spheres"));
}

// pbrt's filters are ours (its default the Gaussian of radius 1.5), and a film of filtered
// samples is the same image from both engines.
TEST(PbrtScenes, PixelFiltersMapAndBothEnginesRenderThemAlike) {
    TempDir dir;
    auto path = dir.write("a.pbrt", "Camera \"perspective\"\nWorldBegin\nShape \"sphere\"\n");
    const PixelFilter default_filter = load_scene(path, collecting()).camera.filter;
    EXPECT_EQ(default_filter.kind, PixelFilter::Kind::Gaussian);
    EXPECT_EQ(default_filter.radius, 1.5f);
    Scene s = load_scene(std::filesystem::path(WAVETRACE_SCENES_DIR) / "cornell-box.pbrt",
                         collecting());
    EXPECT_EQ(s.camera.filter.kind, PixelFilter::Kind::Tent);
    EXPECT_EQ(s.camera.filter.radius, 1.0f);
    const Bvh bvh = Bvh::build(s);
    RenderRequest r;
    r.width = r.height = 24;
    r.spp = 4;
    r.seed = 9;
    Film a(r.width, r.height), b(r.width, r.height), box(r.width, r.height);
    render(s, bvh, r, a);
    r.engine = Engine::Megakernel;
    render(s, bvh, r, b);
    const Image ia = a.mean(), ib = b.mean();
    for (size_t i = 0; i < ia.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ia.pixels[i][c], ib.pixels[i][c], 1e-5f * (1 + ib.pixels[i][c])) << i;
    s.camera.filter = PixelFilter{};  // the box: other rays, another image
    render(s, bvh, r, box);
    EXPECT_NE(box.mean().pixels[100].x, ib.pixels[100].x);
}

// The pbrt file's own meshes become PLY files beside the JSON; the JSON renders the image the
// pbrt file renders, bit for bit.
TEST(PbrtScenes, ConvertWritesJsonAndMeshesThatRenderBitIdentically) {
    TempDir dir;
    const std::filesystem::path pbrt = std::filesystem::path(WAVETRACE_SCENES_DIR) / "cornell-box.pbrt";
    const std::string json = (dir.path() / "out" / "cbox.json").string();
    std::filesystem::create_directories(dir.path() / "out");
    CliResult c = run_cli(dir, "convert '" + pbrt.string() + "' -o '" + json + "'");
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "out" / "cbox-meshes" / "mesh-0.ply"));
    EXPECT_NE(read(json).find("\"cbox-meshes/mesh-7.ply\""), std::string::npos);
    const std::string from_pbrt = (dir.path() / "pbrt.pfm").string();
    const std::string from_json = (dir.path() / "json.pfm").string();
    for (const auto& [scene_file, out] : {std::pair{pbrt.string(), from_pbrt}, {json, from_json}}) {
        CliResult r = run_cli(dir, "render '" + scene_file + "' --spp 2 --seed 3 --width 48 "
                                   "--height 48 -o '" + out + "'");
        ASSERT_EQ(r.code, 0) << r.err;
    }
    EXPECT_EQ(read(from_pbrt), read(from_json));
}

// Bitterli's "Cornell Box" as pbrt-v4 reads it, against Tungsten's render of the same scene
// (his TungstenRender.exr, 1024 x 1024; its image mean (0.196251, 0.127531, 0.036100) read
// with `oiiotool --stats`). The bound: four standard errors of our image mean, from the
// film's own variance, plus 0.3% for the reference's noise and its tent filter at the border.
TEST(PbrtScenes, BitterlisCornellBoxRendersTungstensImageMean) {
    const Scene s = load_scene(std::filesystem::path(WAVETRACE_SCENES_DIR) / "cornell-box.pbrt",
                               collecting());
    EXPECT_EQ(s.triangles.size(), 36u);
    EXPECT_EQ(s.render.max_depth, 66);
    const Bvh bvh = Bvh::build(s);
    RenderRequest r;
    r.width = r.height = 64;
    r.spp = 256;
    r.seed = 5;
    Film film(r.width, r.height);
    render(s, bvh, r, film);
    const Image mean = film.mean(), var = film.variance_of_mean();
    const double reference[3] = {0.196251, 0.127531, 0.036100};
    for (int c = 0; c < 3; ++c) {
        double sum = 0, sum_var = 0;
        for (int y = 0; y < r.height; ++y)
            for (int x = 0; x < r.width; ++x) {
                sum += mean.at(x, y)[c];
                sum_var += var.at(x, y)[c];
            }
        const double n = double(r.width) * r.height;
        const double ours = sum / n, sigma = std::sqrt(sum_var) / n;
        EXPECT_NEAR(ours, reference[c], 4 * sigma + 0.003 * reference[c]) << "channel " << c;
    }
}

// A scale texture of two textures is their product (both checkerboards here).
TEST(PbrtScenes, ScaleOfTwoTexturesIsTheirProduct) {
    TempDir dir;
    auto path = dir.write("a.pbrt", R"(Camera "perspective"
WorldBegin
Texture "a" "spectrum" "checkerboard" "rgb tex1" [0.5 0.5 0.5] "rgb tex2" [1 1 1]
Texture "b" "float" "checkerboard" "float tex1" 0.25 "float tex2" 1
Texture "s" "spectrum" "scale" "texture tex" "a" "texture scale" "b"
Material "diffuse" "texture reflectance" "s"
Shape "sphere"
)");
    Scene s = load_scene(path, collecting());
    EXPECT_TRUE(warnings.empty()) << (warnings.empty() ? "" : warnings.front());
    const Texture& t = s.textures[s.materials[0].albedo];
    ASSERT_EQ(t.kind, TextureKind::Product);
    EXPECT_EQ(s.textures[t.factors[0]].kind, TextureKind::UvChecker);
    EXPECT_EQ(s.textures[t.factors[1]].kind, TextureKind::UvChecker);
    // Both checkerboards have the same cells: the product is 0.125 or 1.
    EXPECT_NEAR(eval_texture(s, s.materials[0].albedo, {0.25f, 0.25f}, {}).x, 0.125f, 1e-6f);
}
