// Scene files: the shipped scenes load, and each class of bad input is reported with the file
// and the place in it.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "scene/delta_lights.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/image/image.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/surface.h"

using namespace wavetrace;

namespace {

const char* kCamera = R"("camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]})";
const char* kMaterials =
    R"("materials": {"white": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}})";

std::string scene_with_objects(const std::string& objects, const std::string& extra = "") {
    return std::string("{") + kCamera + ", " + kMaterials + (extra.empty() ? "" : ", " + extra) +
           ", \"objects\": [" + objects + "]}";
}

// Loads `text` as x.json in a temp folder and returns the error message ("" if it loaded).
std::string load_error(const TempDir& dir, const std::string& text) {
    std::filesystem::path p = dir.write("x.json", text);
    try {
        load_scene(p);
    } catch (const SceneError& e) {
        std::string msg = e.what();
        // Messages start with the file; strip the temp folder for readable expectations.
        EXPECT_EQ(msg.rfind(p.string(), 0), 0u) << msg;
        return msg.substr(p.string().size());
    }
    return "";
}

}  // namespace

TEST(SceneLoader, ShippedScenesLoad) {
    for (const char* name : {"cornell", "cornell-glass", "cornell-mirror", "cornell-smoke",
                             "everything", "bunny", "dragon"}) {
        SCOPED_TRACE(name);
        Scene s = load_scene(scene_path(name));
        EXPECT_GT(s.primitive_count(), 0u);
        EXPECT_FALSE(collect_emitters(s).empty());
    }
    Scene dragon = load_scene(scene_path("dragon"));
    EXPECT_EQ(dragon.triangles.size(), 100000u);
    Scene bunny = load_scene(scene_path("bunny"));
    EXPECT_EQ(bunny.triangles.size(), 69451u);
    Scene everything = load_scene(scene_path("everything"));
    EXPECT_EQ(everything.spheres.size(), 1007u);  // 1000 in the cluster + 7
    EXPECT_EQ(everything.media.size(), 2u);
}

// check_scene() accepts what the loaders build, in every format, and names what a scene built
// in code gets wrong.
TEST(SceneLoader, LoadedScenesPassCheckScene) {
    const std::filesystem::path mitsuba =
        std::filesystem::path(WAVETRACE_REFERENCE_DIR) / "mitsuba3/tests/scenes";
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(WAVETRACE_SCENES_DIR))
        if (e.path().extension() == ".json" || e.path().extension() == ".pbrt")
            files.push_back(e.path());
    for (const auto& e : std::filesystem::recursive_directory_iterator(mitsuba))
        if (e.path().extension() == ".xml" && e.path().filename().string().starts_with("test_"))
            files.push_back(e.path());
    ASSERT_GT(files.size(), 15u);
    for (const auto& f : files) {
        SCOPED_TRACE(f.string());
        LoadOptions quiet;
        quiet.warn = [](const std::string&) {};
        EXPECT_NO_THROW(check_scene(load_scene(f, quiet)));
    }
}

TEST(SceneLoader, CheckSceneNamesWhatIsWrong) {
    auto message = [](const Scene& s) -> std::string {
        try {
            check_scene(s);
        } catch (const SceneError& e) {
            return e.what();
        }
        return "";
    };
    Scene s;
    Material lambert;
    lambert.albedo = s.add_solid({0.5f, 0.5f, 0.5f});
    const MaterialId m = s.add_material(lambert);
    s.add_sphere({{0, 0, -3}, 1.0f, m, kNone});
    EXPECT_EQ(message(s), "");
    s.spheres[0].interior = 3;
    EXPECT_EQ(message(s), "scene: sphere 0: names no medium of the scene");
    s.spheres[0].interior = kNone;
    s.materials[0].albedo = kNone;
    EXPECT_EQ(message(s), "scene: material 0: albedo is needed");
    s.materials[0].albedo = 7;
    EXPECT_EQ(message(s), "scene: material 0: albedo names no texture");
    s.materials[0].albedo = 0;
    Texture checker;
    checker.kind = TextureKind::Checker;
    checker.even = 0;
    checker.odd = 1;  // itself: evaluating it would never end
    s.add_texture(checker);
    EXPECT_EQ(message(s), "scene: texture 1: a checker's cells must be textures added before it");
    s.textures[1].odd = 0;
    s.camera.look_at = s.camera.look_from;
    EXPECT_NE(message(s).find("the camera needs distinct look_from and look_at"), std::string::npos);
}

TEST(SceneLoader, ObjectsAndTransformsBuildTheRightGeometry) {
    TempDir dir;
    std::filesystem::path p = dir.write("x.json", scene_with_objects(R"(
        {"type": "sphere", "center": [1, 0, 0], "radius": 1, "material": "white",
         "transform": [{"scale": 2}, {"rotate": {"axis": [0, 0, 1], "degrees": 90}},
                       {"translate": [0, 0, 5]}]},
        {"type": "box", "min": [0, 0, 0], "max": [1, 2, 3], "material": "white"},
        {"type": "group", "transform": [{"translate": [10, 0, 0]}], "objects": [
            {"type": "quad", "q": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0], "material": "white"}]}
    )"));
    Scene s = load_scene(p);
    ASSERT_EQ(s.spheres.size(), 1u);
    // scale 2 -> centre (2,0,0), r 2; rotate 90 about z -> (0,2,0); translate -> (0,2,5).
    EXPECT_NEAR(s.spheres[0].center.x, 0, 1e-5);
    EXPECT_NEAR(s.spheres[0].center.y, 2, 1e-5);
    EXPECT_NEAR(s.spheres[0].center.z, 5, 1e-5);
    EXPECT_NEAR(s.spheres[0].radius, 2, 1e-5);
    ASSERT_EQ(s.quads.size(), 7u);  // six box faces + one
    EXPECT_EQ(s.quads[6].q.x, 10.0f);
    Aabb box;
    for (int i = 0; i < 6; ++i) box.grow(s.prim_bounds(PrimRef::make(PrimKind::Quad, i)));
    EXPECT_EQ(box.lo, Vec3(0, 0, 0));
    EXPECT_EQ(box.hi, Vec3(1, 2, 3));
    // Box faces point outwards: each face's normal points away from the box centre.
    for (int i = 0; i < 6; ++i) {
        const Quad& q = s.quads[i];
        Vec3 n = cross(q.u, q.v);
        EXPECT_GT(dot(n, q.q + 0.5f * (q.u + q.v) - box.center()), 0.0f) << "face " << i;
    }
}

TEST(SceneLoader, SyntaxErrorGivesLineAndColumn) {
    TempDir dir;
    std::string err = load_error(dir, "{\n  \"camera\": {\n    \"look_from\": [0, 0, -5],,\n");
    EXPECT_EQ(err.rfind(":3:", 0), 0u) << err;
    EXPECT_NE(err.find("invalid JSON"), std::string::npos) << err;
}

TEST(SceneLoader, UnknownKeyIsAnErrorWithASuggestion) {
    TempDir dir;
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, 0], "radus": 1, "material": "white"})")),
        ": /objects/0: missing required key \"radius\" (is \"radus\" a typo?)");
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "radus": 1, "material": "white"})")),
        ": /objects/0/radus: unknown key (did you mean \"radius\"?)");
    std::string err = load_error(dir, std::string("{") + kCamera + ", \"objets\": []}");
    EXPECT_EQ(err, ": /objets: unknown key (did you mean \"objects\"?)");
    // Inside objects, a missing key is reported with its likely misspelling.
    EXPECT_EQ(
        load_error(dir,
                   std::string("{\"camera\": {\"look_from\": [0, 0, 1], \"lok_at\": [0, 0, 0]}}")),
        ": /camera: missing required key \"look_at\" (is \"lok_at\" a typo?)");
    err = load_error(dir, std::string("{") + kCamera + ", \"objects\": [], \"materails\": {}}");
    EXPECT_EQ(err, ": /materails: unknown key (did you mean \"materials\"?)");
}

TEST(SceneLoader, WrongTypesAreNamed) {
    TempDir dir;
    EXPECT_EQ(
        load_error(
            dir, scene_with_objects(
                     R"({"type": "sphere", "center": [0, 0], "radius": 1, "material": "white"})")),
        ": /objects/0/center: expected an array of 3 numbers, got [0,0]");
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, 0], "radius": "big", "material": "white"})")),
        ": /objects/0/radius: expected a positive number, got \"big\"");
    EXPECT_EQ(load_error(dir, scene_with_objects(R"({"type": "cone", "material": "white"})")),
              ": /objects/0/type: unknown object type \"cone\" (expected sphere, quad, box, disk, "
              "cylinder, mesh or group)");
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "chalk"})")),
        ": /objects/0/material: no material named \"chalk\" in /materials");
    EXPECT_EQ(load_error(dir, std::string("{") + kCamera + ", \"objects\": {}}"),
              ": /objects: expected an array, got {}");
}

TEST(SceneLoader, NonFiniteNumbersAreRejected) {
    TempDir dir;
    // NaN is not JSON at all; an overflowing literal parses to infinity or fails to parse.
    EXPECT_NE(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, NaN], "radius": 1, "material": "white"})"))
            .find("invalid JSON"),
        std::string::npos);
    std::string err = load_error(
        dir,
        scene_with_objects(
            R"({"type": "sphere", "center": [0, 0, 1e999], "radius": 1, "material": "white"})"));
    EXPECT_EQ(err, ":1:184: invalid JSON: number overflow parsing '1e999'");
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, 1e39], "radius": 1, "material": "white"})")),
        ": /objects/0/center/2: expected a finite number, got 1e+39");
}

TEST(SceneLoader, NegativeAndZeroSizesAreRejected) {
    TempDir dir;
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "white"})")),
        ": /objects/0/radius: expected a positive number, got -1");
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "sphere", "center": [0, 0, 0], "radius": 0, "material": "white"})")),
        ": /objects/0/radius: expected a positive number, got 0");
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "box", "min": [0, 0, 0], "max": [1, 0, 1], "material": "white"})")),
        ": /objects/0/max: expected max > min in every axis, got [1,0,1]");
    EXPECT_EQ(
        load_error(
            dir,
            scene_with_objects(
                R"({"type": "quad", "q": [0, 0, 0], "u": [1, 0, 0], "v": [2, 0, 0], "material": "white"})")),
        ": /objects/0/v: u and v must not be parallel");
    EXPECT_EQ(
        load_error(dir,
                   scene_with_objects(
                       R"({"type": "box", "min": [0, 0, 0], "max": [1, 1, 1], "material": "white",
                                      "transform": [{"scale": [1, 0, 1]}]})")),
        ": /objects/0/transform/0/scale: expected a non-zero scale within [1e-7, 1e7], got "
        "[1,0,1]");
    EXPECT_EQ(
        load_error(dir,
                   scene_with_objects(
                       R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white",
                                      "transform": [{"scale": [1, 2, 1]}]})")),
        ": /objects/0: a sphere's transform must not scale non-uniformly");
    std::string bad_render =
        std::string("{") + kCamera + R"(, "render": {"width": -5}, "objects": []})";
    EXPECT_EQ(load_error(dir, bad_render),
              ": /render/width: expected an integer in [1, 32768], got -5");
    std::string huge = std::string("{") + kCamera +
                       R"(, "render": {"width": 32768, "height": 32768}, "objects": []})";
    EXPECT_NE(load_error(dir, huge).find("/render: width x height = 1073741824 pixels exceeds"),
              std::string::npos);
    EXPECT_EQ(load_error(dir, std::string("{") + kCamera +
                                  R"(, "render": {"sampler": "halton"}, "objects": []})"),
              ": /render/sampler: expected \"independent\", \"sobol\" or \"zsobol\", got "
              "\"halton\"");
    std::string bad_medium =
        std::string("{") + kCamera +
        R"(, "media": {"fog": {"density": -0.1, "albedo": 1}}, "objects": []})";
    EXPECT_EQ(load_error(dir, bad_medium),
              ": /media/fog/density: expected a positive number, got -0.1");
    // One density per channel: none negative, one positive.
    auto medium_of = [&](const char* density) {
        return std::string("{") + kCamera + R"(, "media": {"fog": {"density": )" + density +
               R"(, "albedo": 1}}, "objects": []})";
    };
    EXPECT_EQ(load_error(dir, medium_of("[0.1, -1, 0.1]")),
              ": /media/fog/density/1: expected a non-negative number, got -1");
    EXPECT_EQ(load_error(dir, medium_of("[0, 0, 0]")),
              ": /media/fog/density: a medium's density must be > 0 in some channel");
    std::string bad_albedo =
        std::string("{") + kCamera +
        R"(, "materials": {"m": {"type": "lambertian", "albedo": [1, -1, 1]}}, "objects": []})";
    EXPECT_EQ(load_error(dir, bad_albedo),
              ": /materials/m/albedo/1: expected a non-negative number, got -1");
    write_image(dir.path() / "t.exr", Image(2, 2));
    EXPECT_EQ(load_error(dir, std::string("{") + kCamera + R"(, "materials": {"m": {"type":
 "lambertian", "albedo": {"type": "image", "file": "t.exr", "wrap": "tile"}}}, "objects": []})"),
              ": /materials/m/albedo/wrap: expected \"repeat\", \"mirror\", \"clamp\" or "
              "\"black\", got \"tile\"");
}

// Disks and cylinders: tessellated where and as they are asked for, and read strictly.
TEST(SceneLoader, DisksAndCylindersAreMeshesWhereAsked) {
    TempDir dir;
    std::filesystem::path p = dir.write(
        "x.json",
        scene_with_objects(
            R"({"type": "disk", "center": [1, 2, 3], "normal": [0, 2, 0], "radius": 0.5,
                "material": "white"},
               {"type": "cylinder", "p0": [0, 0, 0], "p1": [0, 0, 2], "radius": 1,
                "material": "white", "transform": [{"translate": [5, 0, 0]}]})"));
    Scene s = load_scene(p);
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_EQ(s.triangles.size(), 128u + 256u);
    for (const Triangle& t : s.triangles) {
        const Vec3 a = s.positions[t.v[0]], b = s.positions[t.v[1]], c = s.positions[t.v[2]];
        const Vec3 g = cross(b - a, c - a);
        if (t.mesh == 0) {
            EXPECT_NEAR(a.y, 2.0f, 1e-6f);
            EXPECT_LE(length(a - Vec3{1, 2, 3}), 0.5f + 1e-6f);
            EXPECT_GT(g.y, 0.0f) << "the disk faces its normal";
        } else {
            const Vec3 m = (a + b + c) / 3.0f;
            EXPECT_GT(dot(g, Vec3{m.x - 5, m.y, 0}), 0.0f) << "the tube faces outwards";
            EXPECT_NEAR(std::hypot(a.x - 5, a.y), 1.0f, 1e-5f);
        }
    }
    EXPECT_EQ(load_error(dir, scene_with_objects(R"({"type": "disk", "center": [0, 0, 0],
        "normal": [0, 0, 0], "radius": 1, "material": "white"})")),
              ": /objects/0/normal: expected a non-zero vector, got [0,0,0]");
    EXPECT_EQ(load_error(dir, scene_with_objects(R"({"type": "cylinder", "p0": [1, 1, 1],
        "p1": [1, 1, 1], "radius": 1, "material": "white"})")),
              ": /objects/0/p1: p1 must differ from p0");
    EXPECT_EQ(load_error(dir, scene_with_objects(R"({"type": "cylinder", "p0": [0, 0, 0],
        "p1": [0, 0, 1], "radius": 0, "material": "white"})")),
              ": /objects/0/radius: expected a positive number, got 0");
    EXPECT_EQ(load_error(dir, scene_with_objects(R"({"type": "disk", "center": [0, 0, 0],
        "normal": [0, 0, 1], "radius": 1, "height": 2, "material": "white"})"))
                  .find(": /objects/0/height: unknown key"),
              0u);
}

TEST(SceneLoader, PixelFiltersAreReadStrictly) {
    TempDir dir;
    auto scene = [](const std::string& filter) {
        return R"({"camera": {"look_from": [0, 0, 1], "look_at": [0, 0, 0], "filter": )" + filter +
               R"(}, "objects": []})";
    };
    EXPECT_EQ(load_error(dir, scene(R"({"type": "lanczos"})")),
              ": /camera/filter/type: unknown filter type \"lanczos\" (expected box, tent or gaussian)");
    EXPECT_EQ(load_error(dir, scene(R"({"type": "tent", "radius": 0})")),
              ": /camera/filter/radius: expected a number in (0, 8], got 0");
    EXPECT_EQ(load_error(dir, scene(R"({"type": "tent", "sigma": 1})")).substr(0, 31),
              ": /camera/filter/sigma: unknown");
}

TEST(SceneLoader, CameraMustBeWellPosed) {
    TempDir dir;
    EXPECT_EQ(
        load_error(dir,
                   R"({"camera": {"look_from": [0, 0, 0], "look_at": [0, 0, 0]}, "objects": []})"),
        ": /camera/look_at: look_at must differ from look_from");
    EXPECT_EQ(
        load_error(dir,
                   R"({"camera": {"look_from": [0, 0, 0], "look_at": [0, 1, 0]}, "objects": []})"),
        ": /camera: the viewing direction is parallel to the default up [0, 1, 0]; set \"up\"");
    EXPECT_EQ(
        load_error(
            dir,
            R"({"camera": {"look_from": [0, 0, 0], "look_at": [1, 0, 0], "up": [-2, 0, 0]}, "objects": []})"),
        ": /camera/up: up must not be parallel to the viewing direction");
    EXPECT_EQ(load_error(dir, R"({"objects": []})"), ": /: missing required key \"camera\"");
}

// An orthographic camera: parallel rays along the view direction, from a film of view_width x
// view_height centred on look_from (the width following the aspect where not given).
TEST(SceneLoader, OrthographicCameraSendsParallelRaysFromItsFilm) {
    TempDir dir;
    const std::filesystem::path p =
        dir.write("x.json", R"({"camera": {"type": "orthographic", "look_from": [1, 2, 5],
        "look_at": [1, 2, 0], "view_height": 3}, "objects": []})");
    const Scene scene = load_scene(p);
    ASSERT_TRUE(scene.camera.orthographic);
    const CameraRays camera(scene.camera, 40, 20);
    const Ray centre = camera.generate(20.0f, 10.0f, 0.3f, 0.7f);
    const Ray corner = camera.generate(0.0f, 0.0f, 0.3f, 0.7f);
    for (const Ray& r : {centre, corner}) {
        EXPECT_NEAR(r.d.x, 0.0f, 1e-6f);
        EXPECT_NEAR(r.d.y, 0.0f, 1e-6f);
        EXPECT_NEAR(r.d.z, -1.0f, 1e-6f);
        EXPECT_NEAR(r.o.z, 5.0f, 1e-6f);
    }
    EXPECT_NEAR(centre.o.x, 1.0f, 1e-6f);
    EXPECT_NEAR(centre.o.y, 2.0f, 1e-6f);
    // The top-left corner: half the height (1.5) up and half the width (3, from the aspect)
    // left; looking down -z with y up, the image's left is -x.
    EXPECT_NEAR(corner.o.x, 1.0f - 3.0f, 1e-5f);
    EXPECT_NEAR(corner.o.y, 2.0f + 1.5f, 1e-5f);
    EXPECT_EQ(load_error(dir, R"({"camera": {"look_from": [0, 0, 1], "look_at": [0, 0, 0],
        "view_height": 2}, "objects": []})"),
              ": /camera/view_height: view_height is an orthographic camera's");
    EXPECT_EQ(load_error(dir, R"({"camera": {"type": "orthographic", "look_from": [0, 0, 1],
        "look_at": [0, 0, 0], "aperture": 0.1}, "objects": []})"),
              ": /camera/aperture: an orthographic camera has no lens");
    EXPECT_EQ(load_error(dir, R"({"camera": {"type": "fisheye", "look_from": [0, 0, 1],
        "look_at": [0, 0, 0]}, "objects": []})"),
              ": /camera/type: unknown camera type \"fisheye\" (expected perspective or "
              "orthographic)");
}

// A projector's frustum from its field of view on the named axis and its image's aspect (1
// for a colour); its refusals.
TEST(SceneLoader, ProjectorFrustumFollowsItsFieldOfView) {
    TempDir dir;
    auto load = [&](const std::string& light) {
        const std::filesystem::path p =
            dir.write("x.json", std::string("{") + kCamera + R"(, "objects": [], "lights": [)" +
                                    light + "]}");
        return load_scene(p).lights.at(0);
    };
    const Light x = load(R"({"type": "projector", "position": [0, 2, 0], "look_at": [0, 0, 0],
        "fov": 90, "irradiance": [1, 0.5, 0.25], "scale": 2})");
    EXPECT_EQ(x.kind, Light::Kind::Projector);
    EXPECT_NEAR(x.half_width, 1.0f, 1e-6f);
    EXPECT_NEAR(x.half_height, 1.0f, 1e-6f);
    EXPECT_EQ(x.intensity, Color(2.0f, 1.0f, 0.5f));
    EXPECT_EQ(x.texture, kNone);
    EXPECT_NEAR(dot(x.up, x.direction), 0.0f, 1e-6f);
    const Light d = load(R"({"type": "projector", "position": [0, 2, 0], "look_at": [0, 0, 0],
        "fov": 90, "fov_axis": "diagonal"})");
    EXPECT_NEAR(d.half_width, std::sqrt(0.5f), 1e-6f);
    EXPECT_FALSE(x.projects_intensity);
    // pbrt's projection light: the intensity itself, and its power the mean over the frustum's
    // solid angle, 2π/3 for a 90-degree square (a cube's face from its centre).
    const Light i = load(R"({"type": "projector", "position": [0, 2, 0], "look_at": [0, 0, 0],
        "intensity": [1, 1, 1], "scale": 3})");
    EXPECT_TRUE(i.projects_intensity);
    EXPECT_EQ(i.intensity, Color(3.0f));
    Scene one;
    one.lights.push_back(i);
    EXPECT_NEAR(delta_light_power(one, i, 1.0f), 3.0f * 4.0f * kPi / 6.0f, 1e-4f);
    EXPECT_EQ(load_error(dir, std::string("{") + kCamera + R"(, "objects": [], "lights": [
        {"type": "projector", "position": [0, 2, 0], "look_at": [0, 0, 0], "irradiance": 1,
         "intensity": 1}]})"),
              ": /lights/0/intensity: give \"irradiance\" or \"intensity\", not both");
    EXPECT_EQ(load_error(dir, std::string("{") + kCamera + R"(, "objects": [], "lights": [
        {"type": "projector", "position": [0, 2, 0], "look_at": [0, 0, 0], "fov_axis": "z"}]})"),
              ": /lights/0/fov_axis: unknown fov_axis \"z\" (expected x, y, diagonal, smaller or "
              "larger)");
    EXPECT_EQ(load_error(dir, std::string("{") + kCamera + R"(, "objects": [], "lights": [
        {"type": "projector", "position": [0, 2, 0], "look_at": [0, 0, 0], "up": [0, 1, 0]}]})"),
              ": /lights/0/up: up must not lie along the axis");
}

TEST(SceneLoader, MissingAndUnreadableFilesAreNamed) {
    TempDir dir;
    try {
        load_scene(dir.path() / "nope.json");
        FAIL();
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("nope.json: cannot open scene file"),
                  std::string::npos);
    }
    std::string err = load_error(
        dir,
        scene_with_objects(R"({"type": "mesh", "file": "meshes/nope.obj", "material": "white"})"));
    EXPECT_NE(err.find(": /objects/0/file: cannot read mesh '"), std::string::npos) << err;
    EXPECT_NE(err.find("nope.obj': no such file"), std::string::npos) << err;
    std::filesystem::create_directories(dir.path() / "adir.obj");
    err = load_error(
        dir, scene_with_objects(R"({"type": "mesh", "file": "adir.obj", "material": "white"})"));
    EXPECT_NE(err.find("is a directory"), std::string::npos) << err;
    err = load_error(
        dir, scene_with_objects("", R"("background": {"type": "environment", "file": "sky.hdr"})"));
    EXPECT_NE(err.find(": /background/file: cannot open image '"), std::string::npos) << err;
}

TEST(SceneLoader, UnsupportedFormatsAreNamed) {
    TempDir dir;
    dir.write("mesh.xyz", "1 2 3\n");
    std::string err = load_error(
        dir, scene_with_objects(R"({"type": "mesh", "file": "mesh.xyz", "material": "white"})"));
    EXPECT_NE(err.find("unsupported mesh format '.xyz'"), std::string::npos) << err;
    dir.write("tex.png", "this is not a png");
    err = load_error(
        dir,
        std::string("{") + kCamera +
            R"(, "materials": {"m": {"type": "lambertian", "albedo": {"type": "image", "file": "tex.png"}}}, "objects": []})");
    EXPECT_NE(err.find(": /materials/m/albedo/file: "), std::string::npos) << err;
    EXPECT_NE(err.find("cannot read image"), std::string::npos) << err;
    dir.write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    err = load_error(
        dir, scene_with_objects(R"({"type": "mesh", "file": "broken.obj", "material": "white"})"));
    EXPECT_NE(err.find(": /objects/0/file: cannot read mesh"), std::string::npos) << err;
}

TEST(SceneLoader, DegenerateTrianglesAreSkippedAndCounted) {
    TempDir dir;
    // Four triangles: one good, one with zero area (collinear), one repeating a vertex, one
    // good. Written with `v`/`f` only.
    dir.write("m.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nv 1 1 1\n"
              "f 1 2 3\nf 1 2 4\nf 1 1 3\nf 2 5 3\n");
    std::filesystem::path p = dir.write(
        "x.json", scene_with_objects(R"({"type": "mesh", "file": "m.obj", "material": "white"})"));
    static std::string warning;
    warning.clear();
    LoadOptions options;
    options.warn = [](const std::string& w) { warning = w; };
    Scene s = load_scene(p, options);
    EXPECT_EQ(s.triangles.size(), 2u);
    EXPECT_NE(warning.find("2 degenerate triangles skipped"), std::string::npos) << warning;
}

TEST(SceneLoader, MirroringTransformsKeepOutsidesOutside) {
    TempDir dir;
    dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");  // normal +z
    std::filesystem::path p = dir.write("x.json", scene_with_objects(R"(
        {"type": "box", "min": [0, 0, 0], "max": [1, 2, 3], "material": "white",
         "transform": [{"scale": [-1, 1, 1]}]},
        {"type": "mesh", "file": "t.obj", "material": "white", "transform": [{"scale": [1, 1, -1]}]}
    )"));
    Scene s = load_scene(p);
    Aabb box;
    for (int i = 0; i < 6; ++i) box.grow(s.prim_bounds(PrimRef::make(PrimKind::Quad, i)));
    EXPECT_EQ(box.lo, Vec3(-1, 0, 0));
    for (int i = 0; i < 6; ++i) {
        const Quad& q = s.quads[i];
        EXPECT_GT(dot(cross(q.u, q.v), q.q + 0.5f * (q.u + q.v) - box.center()), 0.0f) << i;
    }
    // Mirrored in z, the triangle's front must now face -z.
    const Triangle& t = s.triangles.at(0);
    Vec3 n =
        cross(s.positions[t.v[1]] - s.positions[t.v[0]], s.positions[t.v[2]] - s.positions[t.v[0]]);
    EXPECT_LT(n.z, 0.0f);
}

// `flip_v` reads a mesh's uvs as (u, 1 - v) and gives a quad (a, 1 - b); a mirroring transform
// leaves each point of a quad its texture coordinates (the quad turns to face outwards).
TEST(SceneLoader, FlipVAndMirrorsKeepTextureCoordinates) {
    TempDir dir;
    dir.write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0.25\nvt 1 0.25\nvt 0 1\nf 1/1 2/2 3/3\n");
    std::filesystem::path p = dir.write("x.json", scene_with_objects(R"(
        {"type": "quad", "q": [0, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0], "material": "white",
         "flip_v": true},
        {"type": "quad", "q": [3, 0, 0], "u": [1, 0, 0], "v": [0, 1, 0], "material": "white",
         "transform": [{"scale": [-1, 1, 1]}, {"translate": [9, 0, 0]}]},
        {"type": "mesh", "file": "t.obj", "material": "white", "flip_v": true}
    )"));
    Scene s = load_scene(p);
    EXPECT_TRUE(s.geometric_side_test);  // the default
    EXPECT_FALSE(load_scene(dir.write("y.json", scene_with_objects("", R"("geometric_side_test": false)")))
                     .geometric_side_test);
    ASSERT_EQ(s.uvs.size(), 3u);
    EXPECT_EQ(s.uvs[0].y, 0.75f);
    EXPECT_EQ(s.uvs[2].y, 0.0f);
    const Bvh bvh = Bvh::build(s);
    auto uv_at = [&](float x, float y) {
        const Ray ray{{x, y, 5}, {0, 0, -1}};
        const Hit hit = bvh.intersect(ray);
        EXPECT_TRUE(hit.found());
        return surface_at(s, ray, hit).uv;
    };
    const Vec2 flipped = uv_at(0.25f, 0.125f);
    EXPECT_NEAR(flipped.x, 0.25f, 1e-6f);
    EXPECT_NEAR(flipped.y, 0.875f, 1e-6f);
    // (a, b) = (0.25, 0.125) was at x = 3.25 before the mirror, 9 - 3.25 after.
    const Vec2 mirrored = uv_at(5.75f, 0.125f);
    EXPECT_NEAR(mirrored.x, 0.25f, 1e-6f);
    EXPECT_NEAR(mirrored.y, 0.125f, 1e-6f);
    EXPECT_GT(cross(s.quads[1].u, s.quads[1].v).z, 0.0f);
}

TEST(SceneLoader, ReflectancesAboveOneAndFarGeometryAreRejected) {
    TempDir dir;
    std::string glowing =
        std::string("{") + kCamera +
        R"(, "materials": {"m": {"type": "lambertian", "albedo": [1.2, 0.5, 0.5]}}, "objects": []})";
    EXPECT_EQ(load_error(dir, glowing),
              ": /materials/m/albedo: expected a reflectance with components in [0, 1], got "
              "[1.2,0.5,0.5]");
    EXPECT_EQ(
        load_error(dir, scene_with_objects(R"({"type": "sphere", "center": [0, 0, 0], "radius": 1,
        "material": "white", "transform": [{"translate": [9e6, 0, 0]}, {"translate": [9e6, 0, 0]}]})")),
        ": /objects/0: after its transform the object reaches beyond +-1e7");
    // A misspelt top-level key is reported as such, before the errors it would cause.
    std::string typo = std::string("{") + kCamera +
                       R"(, "materals": {"white": {"type": "lambertian", "albedo": 0.5}},
        "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"}]})";
    EXPECT_EQ(load_error(dir, typo), ": /materals: unknown key (did you mean \"materials\"?)");
}

// A conductor's optical constants and roughness are checked where they are written.
TEST(SceneLoader, ConductorParametersAreValidated) {
    TempDir dir;
    auto with = [](const std::string& gold) {
        return std::string("{") + kCamera + R"(, "materials": {"gold": )" + gold +
               R"(}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "gold"}]})";
    };
    EXPECT_EQ(
        load_error(
            dir,
            with(
                R"({"type": "conductor", "eta": [0.2, 0.4, 1.4], "k": [3.6, 2.4, 1.9], "alpha": 0.1, "distribution": "beckmann"})")),
        "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor"})")), "");  // a full reflector
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "metal": "Au", "alpha": 0.2})")), "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "metal": "none"})")), "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "one_sided": true})")), "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "dielectric", "ior": "bk7", "one_sided": true})")),
              ": /materials/gold/one_sided: only lambertian, metal, mirror, conductor, plastic "
              "and metallic_roughness materials are one-sided or not");
    // Plastic and alpha masks.
    EXPECT_EQ(
        load_error(dir, with(R"({"type": "plastic", "albedo": 0.3, "ior": 1.9, "ext_ior": "air",
        "alpha": 0.1, "distribution": "beckmann", "nonlinear": true, "one_sided": true})")),
        "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "plastic", "alpha": -0.1})")),
              ": /materials/gold/alpha: expected a number in [0.0, 1.0], got -0.1");
    EXPECT_EQ(load_error(dir, with(R"({"type": "plastic", "ior": 0})")),
              ": /materials/gold/ior: expected a positive number, got 0");
    EXPECT_EQ(load_error(dir, with(R"({"type": "plastic", "specular": [1, -1, 1]})")).substr(0, 31),
              ": /materials/gold/specular/1: e");
    EXPECT_EQ(load_error(dir, with(R"({"type": "lambertian", "albedo": 0.5, "opacity": 1.5})"))
                  .substr(0, 27),
              ": /materials/gold/opacity: ");
    EXPECT_EQ(load_error(dir, with(R"({"type": "dielectric", "ior": "glass"})")).substr(0, 72),
              ": /materials/gold/ior: unknown index of refraction \"glass\" (expected a n");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "metal": "gold"})")).substr(0, 65),
              ": /materials/gold/metal: unknown metal \"gold\" (expected none, a-C");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "metal": "Au", "k": 1})")),
              ": /materials/gold/metal: give either \"metal\" or \"eta\" and \"k\", not both");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "eta": [0.2, -0.4, 1.4]})")),
              ": /materials/gold/eta/1: expected a non-negative number, got -0.4");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "eta": 0, "k": [1, 0, 1]})")),
              ": /materials/gold/k: eta and k are both 0 in channel 1: a conductor needs eta > 0 "
              "or k > 0");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "alpha": -0.1})")),
              ": /materials/gold/alpha: expected a number in [0.0, 1.0], got -0.1");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "k": [1, "x", 1]})")),
              ": /materials/gold/k/1: expected a non-negative number, got \"x\"");
    EXPECT_EQ(load_error(dir, with(R"({"type": "conductor", "distribution": "phong"})")),
              ": /materials/gold/distribution: unknown distribution \"phong\" (expected ggx or "
              "beckmann)");
}

TEST(SceneLoader, MetallicRoughnessIsValidated) {
    TempDir dir;
    auto with = [](const std::string& m) {
        return std::string("{") + kCamera + R"(, "materials": {"car": )" + m +
               R"(}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "car"}]})";
    };
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness"})")), "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness", "base_color": [0.8, 0.1, 0.1],
        "metallic": 0, "roughness": 0.3, "ior": "bk7", "transmission": 0.5, "clearcoat": 1,
        "clearcoat_roughness": 0.05, "emission": [2, 2, 2], "two_sided": true,
        "one_sided": true})")),
              "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness", "clearcoat": 1,
        "clearcoat_texture": {"type": "uv_checker", "scale": 0.5, "even": 1, "odd": 0.5},
        "clearcoat_roughness": 0.5, "clearcoat_roughness_texture": [0, 0.2, 0],
        "transmission": 1, "transmission_texture": [0.5, 0, 0],
        "clearcoat_normal_map": [0.5, 0.6, 1]})")),
              "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness",
        "transmission_texture": [0, 2, 0]})")),
              ": /materials/car/transmission_texture: expected a reflectance with components in "
              "[0, 1], got [0,2,0]");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness",
        "clearcoat_texture": [1.5, 0, 0]})")),
              ": /materials/car/clearcoat_texture: expected a reflectance with components in "
              "[0, 1], got [1.5,0,0]");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness", "roughness": -0.2})")),
              ": /materials/car/roughness: expected a number in [0.0, 1.0], got -0.2");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness", "metallic": 1.5})")),
              ": /materials/car/metallic: expected a number in [0.0, 1.0], got 1.5");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness", "ior": -1})")),
              ": /materials/car/ior: expected a positive number, got -1");
    EXPECT_EQ(
        load_error(dir, with(R"({"type": "metallic_roughness", "base_color": [1.2, 0, 0]})"))
            .substr(0, 33),
        ": /materials/car/base_color: expe");
    EXPECT_EQ(load_error(dir, with(R"({"type": "metallic_roughness", "albedo": 0.5})")).substr(0, 36),
              ": /materials/car/albedo: unknown key");
    // An image texture's factor is a colour like any other: a reflectance's within [0, 1].
    dir.write("t.ppm", "P3\n1 1\n255\n10 20 30\n");
    EXPECT_EQ(load_error(dir, with(R"({"type": "lambertian", "albedo": {"type": "image",
        "file": "t.ppm", "factor": 0.5}})")),
              "");
    EXPECT_EQ(load_error(dir, with(R"({"type": "lambertian", "albedo": {"type": "image",
        "file": "t.ppm", "factor": [1, 2, 1]}})"))
                  .substr(0, 38),
              ": /materials/car/albedo/factor: expect");
}

// Lights that are not shapes, checked where they are written.
TEST(SceneLoader, LightsAreValidated) {
    TempDir dir;
    auto with = [](const std::string& lights) {
        return scene_with_objects(
            R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"})",
            R"("lights": )" + lights);
    };
    EXPECT_EQ(
        load_error(dir,
                   with(R"([{"type": "point", "position": [0, 3, 0], "intensity": [1, 2, 3]}])")),
        "");
    EXPECT_EQ(
        load_error(dir, with(R"([{"type": "point", "position": [0, 3, 0], "intensity": -1}])")),
        ": /lights/0/intensity: expected a non-negative number, got -1");
    EXPECT_EQ(load_error(dir, with(R"([{"type": "point", "intensity": 1}])")),
              ": /lights/0: missing required key \"position\"");
    EXPECT_EQ(
        load_error(dir, with(R"([{"type": "point", "position": [0, 1e9, 0], "intensity": 1}])")),
        ": /lights/0/position: coordinate beyond +-1e7, got [0,1000000000.0,0]");
    EXPECT_EQ(load_error(dir, with(R"([{"type": "laser", "position": [0, 1, 0]}])")),
              ": /lights/0/type: unknown light type \"laser\" (expected point, spot, projector "
              "or directional)");
    EXPECT_EQ(
        load_error(
            dir,
            with(
                R"([{"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0], "intensity": 5, "cutoff": 30, "falloff_start": 10, "falloff": "smoothstep"}, {"type": "directional", "direction": [0, -1, 0.2], "irradiance": 2}])")),
        "");
    EXPECT_EQ(
        load_error(
            dir,
            with(
                R"([{"type": "spot", "position": [0, 3, 0], "look_at": [0, 3, 0], "intensity": 5}])")),
        ": /lights/0/look_at: look_at must differ from position");
    EXPECT_EQ(
        load_error(
            dir,
            with(
                R"([{"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0], "intensity": 5, "cutoff": 30, "falloff_start": 40}])")),
        ": /lights/0/falloff_start: expected a number in [0.0, 30.0], got 40");
    EXPECT_EQ(
        load_error(
            dir,
            with(
                R"([{"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0], "intensity": 5, "up": [1, 0, 0]}])")),
        ": /lights/0/up: up orients a projected texture: give one");
    EXPECT_EQ(
        load_error(
            dir,
            with(
                R"([{"type": "spot", "position": [0, 3, 0], "look_at": [0, 0, 0], "intensity": 5, "texture": {"type": "checker", "scale": 1, "even": 1, "odd": 0}, "up": [0, 2, 0]}])")),
        ": /lights/0/up: up must not lie along the axis");
    EXPECT_EQ(
        load_error(dir,
                   with(R"([{"type": "directional", "direction": [0, 0, 0], "irradiance": 1}])"))
            .substr(0, 32),
        ": /lights/0/direction: expected ");
    EXPECT_EQ(load_error(dir, with(R"({"type": "point"})")),
              ": /lights: expected an array, got {\"type\":\"point\"}");
}
