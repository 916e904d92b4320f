// glTF files as whole scenes: the camera and punctual lights that the default scene's node
// hierarchy places, with their parameters; a model without them framed and warned about; a
// malformed hierarchy or out-of-range value refused with the file and the JSON pointer.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_run.h"
#include "load_warnings.h"
#include "temp_dir.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

// A unit quad at z = 0 (two triangles), its buffer inline, with `extra` nodes after the mesh's
// node 0 (which the scene's node list names with `roots`) and `top` members at the top level.
std::string gltf(const std::string& nodes, const std::string& roots, const std::string& top) {
    return R"({"asset": {"version": "2.0"}, "scene": 0,
      "scenes": [{"nodes": [)" + roots + R"(]}],
      "nodes": [{"mesh": 0})" + nodes + R"(],
      "materials": [{"name": "red", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.1, 0.1, 1],
                     "metallicFactor": 0}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
      "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAABAAIAAAACAAMA"}],
      "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                     "min": [-1, -1, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}])" +
           top + "}";
}

// A unit quad's buffer: positions, indices and RGBA colours, white, transparent at y = -1.
constexpr const char* kQuadWithAlpha =
    "AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAABAAIAAAACAAMAAAAAAAAAgD8AAI"
    "A/AACAPwAAAAAAAIA/AACAPwAAgD8AAAAAAACAPwAAgD8AAIA/AACAPwAAgD8AAIA/AACAPwAAgD8=";

void expect_near(Vec3 a, Vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

}  // namespace

TEST(GltfScenes, CameraAndLightsComeFromTheNodeHierarchy) {
    TempDir dir;
    // Node 1 moves everything under it by (0, 0, 3); node 2, its child, turns the camera 90
    // degrees about +y (so it looks along -x) and moves it by (1, 0, 0). Node 3: a point light;
    // node 4: a spot by a column-major matrix (translation (0, 2, 0), axes unchanged: it shines
    // along -z); node 5: a directional light turned 90 degrees about +x (shining along +y).
    const float h = std::sqrt(0.5f);
    const std::string nodes = R"(,
      {"translation": [0, 0, 3], "children": [2]},
      {"camera": 0, "translation": [1, 0, 0], "rotation": [0, )" + std::to_string(h) +
                              ", 0, " + std::to_string(h) + R"(]},
      {"translation": [0, 0.5, 1.5], "extensions": {"KHR_lights_punctual": {"light": 0}}},
      {"matrix": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 2, 0, 1],
       "extensions": {"KHR_lights_punctual": {"light": 1}}},
      {"rotation": [)" + std::to_string(h) + ", 0, 0, " + std::to_string(h) +
                              R"(], "extensions": {"KHR_lights_punctual": {"light": 2}}})";
    const std::string top = R"(,
      "cameras": [{"name": "main", "type": "perspective",
                   "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1}}],
      "extensionsUsed": ["KHR_lights_punctual"],
      "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1, 0.5, 0.25], "intensity": 4, "range": 10},
        {"type": "spot", "intensity": 2, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}},
        {"type": "directional", "color": [0.5, 0.5, 0.5], "intensity": 3}]}})";
    const auto path = dir.write("s.gltf", gltf(nodes, "0, 1, 3, 4, 5", top));
    const Scene s = load_scene(path, collecting());
    EXPECT_EQ(s.name, "s");
    ASSERT_EQ(s.triangles.size(), 2u);
    EXPECT_EQ(s.materials[s.meshes[0].material].kind, MaterialKind::MetallicRoughness);

    expect_near(s.camera.look_from, {1, 0, 3});
    expect_near(s.camera.look_at - s.camera.look_from, {-1, 0, 0});
    expect_near(s.camera.up, {0, 1, 0});
    EXPECT_NEAR(s.camera.vfov, 0.8f * 180.0f / 3.14159265f, 1e-4f);
    EXPECT_EQ(s.render.width, 800);
    EXPECT_EQ(s.render.height, 533);  // 800 / 1.5

    ASSERT_EQ(s.lights.size(), 3u);
    EXPECT_EQ(s.lights[0].kind, Light::Kind::Point);
    expect_near(s.lights[0].position, {0, 0.5f, 1.5f});
    EXPECT_EQ(s.lights[0].intensity, Color(4, 2, 1));
    EXPECT_TRUE(warned("/extensions/KHR_lights_punctual/lights/0: range ignored"));
    EXPECT_EQ(s.lights[1].kind, Light::Kind::Spot);
    expect_near(s.lights[1].position, {0, 2, 0});
    expect_near(s.lights[1].direction, {0, 0, -1});
    EXPECT_NEAR(s.lights[1].cutoff_degrees, 0.5f * 180.0f / 3.14159265f, 1e-4f);
    EXPECT_NEAR(s.lights[1].falloff_start_degrees, 0.2f * 180.0f / 3.14159265f, 1e-4f);
    EXPECT_EQ(s.lights[2].kind, Light::Kind::Directional);
    expect_near(s.lights[2].direction, {0, 1, 0});
    EXPECT_EQ(s.lights[2].intensity, Color(1.5f));
    EXPECT_FALSE(warned("no lights"));
    EXPECT_FALSE(warned("camera"));
}

TEST(GltfScenes, AModelWithoutCameraOrLightsIsFramedAndWarnedAbout) {
    TempDir dir;
    const auto path = dir.write("bare.gltf", gltf("", "0", ""));
    const Scene s = load_scene(path, collecting());
    // The quad's centre in view from +z (a little above), its whole extent inside the field.
    const Vec3 view = normalize(s.camera.look_at - s.camera.look_from);
    expect_near(s.camera.look_at, {0, 0, 0});
    EXPECT_LT(view.z, -0.9f);
    const float half = 0.5f * s.camera.vfov * 3.14159265f / 180.0f;
    EXPECT_GT(length(s.camera.look_from) * std::sin(half), std::sqrt(2.0f));
    EXPECT_TRUE(warned("no camera in the default scene; framing the model from +z"));
    EXPECT_TRUE(warned("no lights and no emissive materials: the image will be black"));
}

TEST(GltfScenes, MalformedHierarchiesAreRefusedWithThePlace) {
    TempDir dir;
    auto error = [&](const std::string& nodes, const std::string& roots, const std::string& top) {
        const auto path = dir.write("bad.gltf", gltf(nodes, roots, top));
        try {
            load_scene(path, collecting());
        } catch (const SceneError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind(path.string() + ": ", 0), 0u) << msg;
            return msg.substr(path.string().size() + 2);
        }
        return std::string();
    };
    EXPECT_EQ(error(R"(, {"extensions": {"KHR_lights_punctual": {"light": 3}}})", "0, 1", ""),
              "/nodes/1/extensions/KHR_lights_punctual/light: expected an index below 0");
    // Cycles are refused before Assimp reads the file (check_gltf); indices out of range
    // Assimp's reader refuses, with its own words.
    EXPECT_EQ(error(R"(, {"children": [2]}, {"children": [1]})", "0, 1", ""),
              "/nodes: the hierarchy has a cycle");
    EXPECT_EQ(error(R"(, {"camera": 0})", "0, 1",
                    R"(, "cameras": [{"type": "perspective", "perspective": {"yfov": -1}}])"),
              "/cameras/0/perspective/yfov: expected radians in (0, 3.12)");
    EXPECT_EQ(error(R"(, {"translation": [0, 0, "x"]})", "0, 1", ""),
              "/nodes/1/translation: expected finite numbers");
    EXPECT_NE(error("", "0, 7", "").find("index 7 is out of bounds"), std::string::npos);
    EXPECT_EQ(
        error(R"(, {"extensions": {"KHR_lights_punctual": {"light": 0}}})", "0, 1",
              R"(, "extensions": {"KHR_lights_punctual": {"lights": [{"type": "area"}]}})"),
        "/extensions/KHR_lights_punctual/lights/0/type: unknown light type \"area\"");
    // An orthographic camera needs both magnifications.
    EXPECT_EQ(
        error(R"(, {"camera": 0})", "0, 1",
              R"(, "cameras": [{"type": "orthographic", "orthographic": {"xmag": 1}}])"),
        "/cameras/0/orthographic: expected xmag and ymag in (0, 1e7], their ratio within 100");
}

// An orthographic camera: its view 2 xmag wide and 2 ymag high, the image's aspect theirs.
TEST(GltfScenes, OrthographicCameraKeepsItsMagnifications) {
    TempDir dir;
    const auto path =
        dir.write("ortho.gltf", gltf(R"(, {"camera": 0, "translation": [0, 0, 4]})", "0, 1",
                                     R"(, "cameras": [{"type": "orthographic", "orthographic":
                               {"xmag": 2, "ymag": 1, "znear": 0.1, "zfar": 10}}])"));
    const Scene s = load_scene(path, collecting());
    EXPECT_TRUE(s.camera.orthographic);
    EXPECT_FLOAT_EQ(s.camera.view_width, 4.0f);
    EXPECT_FLOAT_EQ(s.camera.view_height, 2.0f);
    EXPECT_EQ(s.render.width, 800);
    EXPECT_EQ(s.render.height, 400);
    EXPECT_EQ(s.camera.look_from, Vec3(0, 0, 4));
    EXPECT_FALSE(warned("camera"));
}

// --camera picks a camera by its name (or its node's); a name the file lacks is an error that
// lists the names there are; a JSON scene refuses the option. Through the CLI: exit 2, no image,
// and with a right name an image.
TEST(GltfScenes, CameraIsChosenByName) {
    TempDir dir;
    const std::string nodes = R"(,
      {"camera": 0, "translation": [0, 0, 3]},
      {"name": "side", "camera": 1, "translation": [0, 0, 5],
       "extensions": {"KHR_lights_punctual": {"light": 0}}})";
    const std::string top = R"(,
      "cameras": [{"name": "front", "type": "perspective", "perspective": {"yfov": 0.5}},
                  {"type": "perspective", "perspective": {"yfov": 0.6}}],
      "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point"}]}})";
    const auto path = dir.write("two.gltf", gltf(nodes, "0, 1, 2", top));
    LoadOptions options = collecting();
    EXPECT_EQ(load_scene(path, options).camera.look_from, Vec3(0, 0, 3));
    EXPECT_TRUE(warned("2 cameras; rendering through the first, \"front\" (/nodes/1)"));
    options.camera = "side";  // the node's name: the camera has none
    EXPECT_EQ(load_scene(path, options).camera.look_from, Vec3(0, 0, 5));
    options.camera = "top";
    try {
        load_scene(path, options);
        ADD_FAILURE() << "expected an error";
    } catch (const SceneError& e) {
        EXPECT_EQ(std::string(e.what()), path.string() +
                                             ": no camera named \"top\" (the file has "
                                             "\"front\", \"side\")");
    }

    const auto json = dir.write("s.json", R"({"camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0]},
        "objects": [{"type": "mesh", "file": "two.gltf", "materials": "file"}]})");
    CliResult r = run_cli(dir, "render '" + json.string() + "' --camera side -o '" +
                                   (dir.path() / "a.png").string() + "'");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--camera chooses among a glTF file's cameras"), std::string::npos)
        << r.err;
    r = run_cli(dir, "render '" + path.string() + "' --camera top --spp 1 -o '" +
                         (dir.path() / "b.png").string() + "'");
    EXPECT_EQ(r.code, 2);
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "b.png"));
    r = run_cli(dir, "render '" + path.string() +
                         "' --camera side --spp 1 --width 32 --height 24 -o '" +
                         (dir.path() / "c.png").string() + "'");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "c.png"));
}

// COLOR_0 multiplies the base colour (glTF 2.0, 3.7.2.1): the quad's corners red, green, blue
// and white, its base colour (0.5, 1, 0.25); each corner's albedo is their product, and a point
// inside a triangle the product with the interpolated colour.
TEST(GltfScenes, VertexColorsMultiplyTheBaseColour) {
    TempDir dir;
    const auto path = dir.write("colors.gltf", R"({"asset": {"version": "2.0"}, "scene": 0,
      "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 1, 0.25, 1],
                     "metallicFactor": 0}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 2}, "indices": 1,
                                  "material": 0}]}],
      "buffers": [{"byteLength": 108, "uri": "data:application/octet-stream;base64,AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAABAAIAAAACAAMAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AACAPwAAgD8AAIA/"}],
      "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12},
                      {"buffer": 0, "byteOffset": 60, "byteLength": 48}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                     "min": [-1, -1, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC3"}]})");
    const Scene s = load_scene(path);
    ASSERT_EQ(s.triangles.size(), 2u);
    const TextureId albedo = s.materials[s.meshes[0].material].albedo;
    ASSERT_EQ(s.textures[albedo].kind, TextureKind::Product);
    auto corner = [&](Point3 p) {  // the file's colour at a corner of the quad
        return p.x < 0 ? (p.y < 0 ? Color(1, 0, 0) : Color(1, 1, 1))
                       : (p.y < 0 ? Color(0, 1, 0) : Color(0, 0, 1));
    };
    const Color base(0.5f, 1.0f, 0.25f);
    for (uint32_t t = 0; t < 2; ++t) {
        const Triangle& tri = s.triangles[t];
        Color mixed(0.0f);
        const float b[3] = {0.5f, 0.25f, 0.25f};
        for (int k = 0; k < 3; ++k) {
            const Color at_corner = eval_texture(
                s, albedo, TexturePoint{{}, {}, t, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f});
            expect_near(at_corner, base * corner(s.positions[tri.v[k]]));
            mixed += b[k] * corner(s.positions[tri.v[k]]);
        }
        expect_near(eval_texture(s, albedo, TexturePoint{{}, {}, t, 0.25f, 0.25f}), base * mixed);
    }
}

// COLOR_0's alpha multiplies the base colour's (glTF 2.0, 3.7.2.1): the quad's corners at
// y = -1 transparent, at y = 1 opaque, the base colour's alpha 0.8. With alphaMode MASK
// (cutoff 0.5) the coverage is 0 below y = 0.25 and 1 above, where 0.8 times the interpolated
// alpha crosses 0.5; with BLEND it is that product itself; OPAQUE ignores it.
TEST(GltfScenes, VertexAlphaMultipliesTheBaseColoursAlpha) {
    TempDir dir;
    const auto write = [&](const std::string& name, const std::string& mode) {
        return dir.write(name, R"({"asset": {"version": "2.0"}, "scene": 0,
      "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.8],
                     "metallicFactor": 0}, "alphaMode": ")" +
                                   mode + R"(", "alphaCutoff": 0.5}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "COLOR_0": 2}, "indices": 1,
                                  "material": 0}]}],
      "buffers": [{"byteLength": 128, "uri": "data:application/octet-stream;base64,)" +
                                   std::string(kQuadWithAlpha) + R"("}],
      "bufferViews": [{"buffer": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12},
                      {"buffer": 0, "byteOffset": 64, "byteLength": 64}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                     "min": [-1, -1, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"},
                    {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC4"}]})");
    };
    // The coverage at the point of triangle t whose barycentrics are b1, b2.
    const auto coverage = [](const Scene& s, uint32_t t, float b1, float b2) {
        const TextureId opacity = s.materials[s.meshes[0].material].opacity;
        return opacity == kNone ? 1.0f
                                : eval_texture(s, opacity, TexturePoint{{}, {}, t, b1, b2}).x;
    };
    // The alpha interpolated at that point, from the file's corners.
    const auto alpha_at = [](const Scene& s, uint32_t t, float b1, float b2) {
        const Triangle& tri = s.triangles[t];
        const float b[3] = {1.0f - b1 - b2, b1, b2};
        float a = 0.0f;
        for (int k = 0; k < 3; ++k) a += b[k] * (s.positions[tri.v[k]].y > 0.0f ? 1.0f : 0.0f);
        return a;
    };
    const Scene mask = load_scene(write("mask.gltf", "MASK"));
    const Scene blend = load_scene(write("blend.gltf", "BLEND"));
    const Scene opaque = load_scene(write("opaque.gltf", "OPAQUE"));
    ASSERT_EQ(mask.triangles.size(), 2u);
    int cut = 0, kept = 0;
    for (uint32_t t = 0; t < 2; ++t)
        for (const auto& [b1, b2] :
             {std::pair{0.1f, 0.1f}, {0.8f, 0.1f}, {0.1f, 0.8f}, {0.3f, 0.3f}}) {
            const float a = 0.8f * alpha_at(mask, t, b1, b2);
            EXPECT_EQ(coverage(mask, t, b1, b2), a >= 0.5f ? 1.0f : 0.0f)
                << t << " " << b1 << " " << b2;
            (a >= 0.5f ? kept : cut)++;
            EXPECT_NEAR(coverage(blend, t, b1, b2), a, 1e-6f);
            EXPECT_EQ(coverage(opaque, t, b1, b2), 1.0f);
        }
    EXPECT_GT(cut, 0);
    EXPECT_GT(kept, 0);
}
