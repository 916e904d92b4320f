// Mesh files through Assimp: the same cube written as OBJ (quads, negative indices, MTL),
// ASCII PLY (extra vertex properties) and binary PLY must load as the same triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>

#include "temp_dir.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

const Point3 kCube[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
// Outward-facing quads (counter-clockwise seen from outside).
const int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                          {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};

std::string obj_text() {
    std::string s = "mtllib cube.mtl\no cube\n";
    for (const Point3& p : kCube)
        s += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) +
             "\n";
    s += "usemtl grey\n";
    for (const auto& f : kFaces)  // negative (relative) indices: -8 is the first vertex
        s += "f " + std::to_string(f[0] - 8) + " " + std::to_string(f[1] - 8) + " " +
             std::to_string(f[2] - 8) + " " + std::to_string(f[3] - 8) + "\n";
    return s;
}

std::string ply_ascii_text() {
    std::string s =
        "ply\nformat ascii 1.0\ncomment cube\nelement vertex 8\nproperty float x\n"
        "property float y\nproperty float z\nproperty float confidence\nelement face 6\n"
        "property list uchar int vertex_indices\nend_header\n";
    for (const Point3& p : kCube)
        s += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + " 0.5\n";
    for (const auto& f : kFaces)
        s += "4 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
             " " + std::to_string(f[3]) + "\n";
    return s;
}

std::string ply_binary_text() {
    std::string s =
        "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\n"
        "property float y\nproperty float z\nelement face 6\n"
        "property list uchar int vertex_indices\nend_header\n";
    for (const Point3& p : kCube) s.append(reinterpret_cast<const char*>(&p), sizeof(Point3));
    for (const auto& f : kFaces) {
        s.push_back(4);
        s.append(reinterpret_cast<const char*>(f), 4 * sizeof(int));
    }
    return s;
}

// The loaded triangles as sorted lists of vertex positions, and every normal's direction.
std::vector<std::array<float, 9>> triangles_of(const TempDir& dir, const std::string& file) {
    auto p = dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "lambertian", "albedo": 0.5}},
        "objects": [{"type": "mesh", "file": ")" +
                                     file + R"(", "material": "m"}]})");
    Scene s = load_scene(p);
    std::vector<std::array<float, 9>> out;
    for (const Triangle& t : s.triangles) {
        Point3 v[3] = {s.positions[t.v[0]], s.positions[t.v[1]], s.positions[t.v[2]]};
        // Outward: the normal points away from the cube's centre.
        Vec3 n = cross(v[1] - v[0], v[2] - v[0]);
        EXPECT_GT(dot(n, (v[0] + v[1] + v[2]) / 3.0f - Vec3(0.5f)), 0.0f) << file;
        // Rotate so the smallest vertex comes first (the winding is kept).
        int first = 0;
        for (int k = 1; k < 3; ++k)
            if (std::memcmp(&v[k], &v[first], sizeof(Point3)) < 0) first = k;
        std::array<float, 9> key;
        for (int k = 0; k < 3; ++k)
            for (int c = 0; c < 3; ++c) key[3 * k + c] = v[(first + k) % 3][c];
        out.push_back(key);
    }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace

TEST(MeshFiles, ObjAndPlyVariantsLoadTheSameTriangles) {
    TempDir dir;
    dir.write("cube.obj", obj_text());
    dir.write("cube.mtl", "newmtl grey\nKd 0.5 0.5 0.5\n");
    dir.write("cube_ascii.ply", ply_ascii_text());
    dir.write("cube_binary.ply", ply_binary_text());
    auto obj = triangles_of(dir, "cube.obj");
    EXPECT_EQ(obj.size(), 12u);  // six quads, fan-triangulated
    EXPECT_EQ(triangles_of(dir, "cube_ascii.ply"), obj);
    EXPECT_EQ(triangles_of(dir, "cube_binary.ply"), obj);
}

TEST(MeshFiles, GltfLoads) {
    // A one-triangle glTF 2.0 file with its buffer inline (base64 of three float3 positions).
    TempDir dir;
    dir.write("tri.gltf", R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "buffers": [{"byteLength": 36,
        "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]}]
    })");
    auto p = dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "lambertian", "albedo": 0.5}},
        "objects": [{"type": "mesh", "file": "tri.gltf", "material": "m"}]})");
    Scene s = load_scene(p);
    ASSERT_EQ(s.triangles.size(), 1u);
    Aabb b = s.bounds();
    EXPECT_EQ(b.lo, Vec3(0, 0, 0));
    EXPECT_EQ(b.hi, Vec3(1, 1, 0));
}
