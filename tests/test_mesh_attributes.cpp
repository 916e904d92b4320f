// PLY meshes through our own reader and the attributes they carry (Mitsuba 3's mesh
// attributes): the same mesh written as ASCII, binary little-endian and binary big-endian PLY
// loads as the same triangles and attributes, named as Mitsuba names them; a mesh_attribute
// texture interpolates a vertex attribute by the hit's barycentrics and takes a face attribute
// of the triangle hit, also where a degenerate face was skipped before it; what cannot read an
// attribute is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "cli_run.h"
#include "temp_dir.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

using namespace wavetrace;

namespace {

// Five vertices; a quad, a degenerate triangle and a triangle.
const float kXyz[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
const float kSt[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5f, 0.25f}};
const unsigned char kRgb[5][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {10, 20, 30}, {1, 2, 3}};
const float kWeight[5] = {0.5f, 0.25f, 0.125f, 1.0f, 2.0f};
const std::vector<std::vector<int>> kFaces = {{0, 1, 2, 3}, {0, 0, 1}, {1, 4, 2}};
const float kFaceColor[3][3] = {{0.1f, 0.2f, 0.3f}, {9, 9, 9}, {0.4f, 0.5f, 0.6f}};
const float kFaceWeight[3] = {0.75f, 9, 0.375f};

const char* kHeader =
    "comment vertex: st as uv, red green blue a colour, weight_0 one channel, quality none\n"
    "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
    "property float s\nproperty float t\nproperty uchar red\nproperty uchar green\n"
    "property uchar blue\nproperty float weight_0\nproperty float quality\n"
    "comment face: color_0..2 a colour, weight_0 one channel, d_x d_y two (none)\n"
    "element face 3\nproperty list uchar int vertex_indices\nproperty float color_0\n"
    "property float color_1\nproperty float color_2\nproperty double weight_0\n"
    "property float d_x\nproperty float d_y\nend_header\n";

std::string ascii_ply() {
    std::string s = std::string("ply\nformat ascii 1.0\n") + kHeader;
    for (int v = 0; v < 5; ++v)
        s += std::to_string(kXyz[v][0]) + " " + std::to_string(kXyz[v][1]) + " " +
             std::to_string(kXyz[v][2]) + " " + std::to_string(kSt[v][0]) + " " +
             std::to_string(kSt[v][1]) + " " + std::to_string(kRgb[v][0]) + " " +
             std::to_string(kRgb[v][1]) + " " + std::to_string(kRgb[v][2]) + " " +
             std::to_string(kWeight[v]) + " 7\n";
    for (size_t f = 0; f < kFaces.size(); ++f) {
        s += std::to_string(kFaces[f].size());
        for (int i : kFaces[f]) s += " " + std::to_string(i);
        for (float c : kFaceColor[f]) s += " " + std::to_string(c);
        s += " " + std::to_string(kFaceWeight[f]) + " 1 2\n";
    }
    return s;
}

template <class T>
void put(std::string& s, T value, bool big) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof b);
    if (big) std::reverse(b, b + sizeof b);
    s.append(b, sizeof b);
}

std::string binary_ply(bool big) {
    std::string s = std::string("ply\nformat ") +
                    (big ? "binary_big_endian" : "binary_little_endian") + " 1.0\n" + kHeader;
    for (int v = 0; v < 5; ++v) {
        for (float x : kXyz[v]) put(s, x, big);
        for (float x : kSt[v]) put(s, x, big);
        for (unsigned char c : kRgb[v]) put(s, c, big);
        put(s, kWeight[v], big);
        put(s, 7.0f, big);
    }
    for (size_t f = 0; f < kFaces.size(); ++f) {
        put(s, static_cast<unsigned char>(kFaces[f].size()), big);
        for (int i : kFaces[f]) put(s, i, big);
        for (float c : kFaceColor[f]) put(s, c, big);
        put(s, double(kFaceWeight[f]), big);
        put(s, 1.0f, big);
        put(s, 2.0f, big);
    }
    return s;
}

std::string scene_json(const std::string& mesh, const std::string& texture) {
    return R"({"camera": {"look_from": [0.5, 0.5, 3], "look_at": [0.5, 0.5, 0]},
 "materials": {"m": {"type": "lambertian", "albedo": )" +
           texture + R"(}},
 "objects": [{"type": "mesh", "file": ")" +
           mesh + R"(", "material": "m"}]})";
}

const MeshAttribute& attribute(const Scene& s, const std::string& name) {
    const MeshAttribute* a = s.mesh_attribute(0, name);
    EXPECT_NE(a, nullptr) << name;
    static const MeshAttribute none;
    return a ? *a : none;
}

}  // namespace

TEST(MeshAttributes, PlyFormatsReadAlikeWithMitsubasNames) {
    TempDir dir;
    std::vector<Scene> scenes;
    for (const auto& [name, text] : {std::pair{"a.ply", ascii_ply()},
                                     {"le.ply", binary_ply(false)},
                                     {"be.ply", binary_ply(true)}}) {
        dir.write(name, text);
        const auto p = dir.write("s.json", scene_json(name, "[0.5, 0.5, 0.5]"));
        scenes.push_back(load_scene(p));
    }
    for (const Scene& s : scenes) {
        // The quad fanned into two triangles, the degenerate one skipped: three.
        ASSERT_EQ(s.triangles.size(), 3u);
        ASSERT_EQ(s.positions.size(), 5u);
        EXPECT_EQ(s.uvs[4].x, 0.5f);
        EXPECT_EQ(s.uvs[4].y, 0.25f);
        std::vector<std::string> names;
        for (const MeshAttribute& a : s.mesh_attributes) names.push_back(a.name);
        EXPECT_EQ(names, (std::vector<std::string>{"vertex_color", "vertex_weight", "face_color",
                                                   "face_weight"}));
        const MeshAttribute& vc = attribute(s, "vertex_color");
        EXPECT_EQ(vc.channels, 3);
        EXPECT_FALSE(vc.per_face);
        EXPECT_EQ(vc.values[3], Color(10, 20, 30));  // integers as they are (as Mitsuba reads them)
        EXPECT_EQ(attribute(s, "vertex_weight").channels, 1);
        EXPECT_EQ(attribute(s, "vertex_weight").values[1], Color(0.25f));
        const MeshAttribute& fw = attribute(s, "face_weight");
        ASSERT_EQ(fw.values.size(), 3u);  // one per kept triangle
        EXPECT_EQ(fw.values[0], Color(0.75f));
        EXPECT_EQ(fw.values[1], Color(0.75f));
        EXPECT_EQ(fw.values[2], Color(0.375f));
        EXPECT_EQ(attribute(s, "face_color").values[2], Color(0.4f, 0.5f, 0.6f));
    }
    for (size_t k = 1; k < scenes.size(); ++k) {
        EXPECT_EQ(scenes[k].positions, scenes[0].positions);
        for (size_t t = 0; t < 3; ++t)
            EXPECT_TRUE(std::equal(scenes[k].triangles[t].v, scenes[k].triangles[t].v + 3,
                                   scenes[0].triangles[t].v));
        for (size_t a = 0; a < 4; ++a)
            EXPECT_EQ(scenes[k].mesh_attributes[a].values, scenes[0].mesh_attributes[a].values);
    }
}

TEST(MeshAttributes, TextureInterpolatesVerticesAndTakesTheFaceHit) {
    TempDir dir;
    dir.write("m.ply", binary_ply(false));
    const Scene s = load_scene(dir.write(
        "s.json", scene_json("m.ply", R"({"type": "mesh_attribute", "name": "vertex_color"})")));
    const TextureId t = s.materials[0].albedo;
    // Triangle 2 (the file's third face) is (1, 4, 2): red-green-blue of (0,255,0), (1,2,3),
    // (0,0,255).
    const Triangle& tri = s.triangles[2];
    ASSERT_EQ(tri.v[1] - s.meshes[0].first_vertex, 4u);
    const Color c = eval_texture(s, t, TexturePoint{{}, {}, 2, 0.25f, 0.5f});
    const Color want = 0.25f * Color(0, 255, 0) + 0.25f * Color(1, 2, 3) + 0.5f * Color(0, 0, 255);
    EXPECT_NEAR(c.x, want.x, 1e-4f);
    EXPECT_NEAR(c.y, want.y, 1e-4f);
    EXPECT_NEAR(c.z, want.z, 1e-4f);

    const Scene f = load_scene(
        dir.write("f.json", scene_json("m.ply", R"({"type": "mesh_attribute", "name": "face_color",
                                          "scale": 2})")));
    const TextureId ft = f.materials[0].albedo;
    for (float b : {0.1f, 0.6f}) {
        EXPECT_EQ(eval_texture(f, ft, TexturePoint{{}, {}, 1, b, 0.2f}),
                  2.0f * Color(0.1f, 0.2f, 0.3f));
        // The face after the skipped one keeps its own value.
        EXPECT_EQ(eval_texture(f, ft, TexturePoint{{}, {}, 2, b, 0.2f}),
                  2.0f * Color(0.4f, 0.5f, 0.6f));
    }
}

TEST(MeshAttributes, WhatCannotReadAnAttributeIsRefused) {
    TempDir dir;
    dir.write("m.ply", ascii_ply());
    const std::string attr = R"({"type": "mesh_attribute", "name": "vertex_color"})";
    auto refused = [&](const std::string& json, const std::string& message) {
        const auto p = dir.write("x.json", json);
        try {
            (void)load_scene(p);
            ADD_FAILURE() << "loaded: " << json;
        } catch (const SceneError& e) {
            EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
        }
    };
    refused(scene_json("m.ply", R"({"type": "mesh_attribute", "name": "vertex_albedo"})"),
            "/objects/0: its material reads the mesh attribute \"vertex_albedo\", which mesh "
            "'m.ply' does not have (it has \"vertex_color\", \"vertex_weight\", \"face_color\", "
            "\"face_weight\")");
    refused(scene_json("m.ply", R"({"type": "mesh_attribute", "name": "color"})"),
            "/materials/m/albedo/name: expected a name that starts with \"vertex_\" or \"face_\"");
    const std::string sphere =
        R"({"camera": {"look_from": [0, 0, 3], "look_at": [0, 0, 0]},
 "materials": {"m": {"type": "lambertian", "albedo": )" +
        attr + R"(}},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "m"}]})";
    refused(sphere, "/objects/0: its material reads a mesh attribute, and only meshes have them");
    const std::string emitter =
        R"({"camera": {"look_from": [0, 0, 3], "look_at": [0, 0, 0]},
 "materials": {"m": {"type": "diffuse_light", "radiance": )" +
        attr + R"(}},
 "objects": [{"type": "mesh", "file": "m.ply", "material": "m"}]})";
    refused(emitter, "/materials/m: its emission reads a mesh attribute");
    const std::string medium =
        R"({"camera": {"look_from": [0, 0, 3], "look_at": [0, 0, 0]},
 "media": {"fog": {"density": 1, "albedo": )" +
        attr + R"(}},
 "objects": [{"type": "mesh", "file": "m.ply", "interior": "fog"}]})";
    refused(medium, "/media/fog/albedo: a mesh attribute is read only on a mesh's surface");
}

// `wavetrace info` names each attribute the meshes carry, where it is stored and its channels.
TEST(MeshAttributes, InfoListsThem) {
    TempDir dir;
    dir.write("m.ply", binary_ply(false));
    const auto scene = dir.write("s.json", scene_json("m.ply", "[0.5, 0.5, 0.5]"));
    const CliResult r = run_cli(dir, "info '" + scene.string() + "'");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(
        r.out.find("attributes   vertex_color (per vertex, 3 channels, 1 mesh), vertex_weight "
                   "(per vertex, 1 channel, 1 mesh), face_color (per face, 3 channels, 1 "
                   "mesh), face_weight (per face, 1 channel, 1 mesh)\n"),
        std::string::npos)
        << r.out;
}

// An OBJ's vertex colours (`v x y z r g b`, as Blender and MeshLab write them) are the
// `vertex_color` attribute, which a texture reads at a hit as it reads a PLY's.
TEST(MeshAttributes, ObjVertexColoursAreAnAttribute) {
    TempDir dir;
    dir.write("c.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 1 0 0 0 1\nf 1 2 3\n");
    const Scene s = load_scene(dir.write(
        "s.json", scene_json("c.obj", R"({"type": "mesh_attribute", "name": "vertex_color"})")));
    ASSERT_EQ(s.mesh_attributes.size(), 1u);
    EXPECT_EQ(s.mesh_attributes[0].name, "vertex_color");
    EXPECT_FALSE(s.mesh_attributes[0].per_face);
    ASSERT_EQ(s.triangles.size(), 1u);
    const TextureId albedo = s.materials[s.meshes[0].material].albedo;
    const Color c = eval_texture(s, albedo, TexturePoint{{}, {}, 0, 0.25f, 0.5f});
    // The corners' colours weighted by the barycentrics (0.25, 0.25, 0.5), in the file's order.
    const Triangle& t = s.triangles[0];
    Color expected(0.0f);
    const float b[3] = {0.25f, 0.25f, 0.5f};
    for (int k = 0; k < 3; ++k) {
        const Point3 p = s.positions[t.v[k]];
        expected += b[k] * (p.x == 0 ? Color(1, 0, 0) : p.y == 0 ? Color(0, 1, 0) : Color(0, 0, 1));
    }
    EXPECT_NEAR(c.x, expected.x, 1e-6f);
    EXPECT_NEAR(c.y, expected.y, 1e-6f);
    EXPECT_NEAR(c.z, expected.z, 1e-6f);
}
