// Mesh files through Assimp: the same cube written as OBJ (quads, negative indices, MTL),
// ASCII PLY (extra vertex properties) and binary PLY must load as the same triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <string>

#include "bsdfs/bsdf.h"
#include "scene/material_lookup.h"
#include "temp_dir.h"
#include "wavetrace/image/image.h"
#include "wavetrace/loaders/load_scene.h"
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

// The data of a glTF file's one triangle with uvs, its buffer inline (base64 of three float3
// positions and three float2 uvs): the keys after a file's materials and images.
const std::string kTexturedTriangle = R"("buffers": [{"byteLength": 60,
        "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}],
      "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}])";

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

// glTF materials become metallic_roughness with the file's factors (pbrMetallicRoughness,
// KHR_materials_ior, _transmission, _clearcoat, emissive), the textures beside the file as image
// textures times their factors (the coat's normal map its own), alpha modes as opacity; a texture
// embedded in the file (here a data URI) is decoded from memory; extensions not read are named.
TEST(MeshFiles, GltfMaterialsMapToMetallicRoughness) {
    TempDir dir;
    Image base(2, 2), mr(2, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            base.at(x, y) = Color(1.0f);
            mr.at(x, y) = Color(0.0f, 0.5f, 1.0f);  // roughness and metallic
        }
    write_image(dir.path() / "base.png", base);
    write_image(dir.path() / "mr.png", mr);
    dir.write("two.gltf", R"({
      "asset": {"version": "2.0"},
      "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_clearcoat",
                         "KHR_materials_ior", "KHR_materials_emissive_strength",
                         "KHR_materials_sheen", "KHR_texture_transform"],
      "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0},
                                 {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 1},
                                 {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 2},
                                 {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 3}]}],
      "materials": [
        {"name": "coated", "doubleSided": true, "emissiveFactor": [1, 0.5, 0],
         "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.4, 1],
                                  "metallicFactor": 0.3, "roughnessFactor": 0.6},
         "extensions": {"KHR_materials_transmission": {"transmissionFactor": 0.4,
                                                       "transmissionTexture": {"index": 1}},
                        "KHR_materials_clearcoat": {"clearcoatFactor": 0.7,
                                                    "clearcoatRoughnessFactor": 0.2,
                                                    "clearcoatTexture": {"index": 0},
                                                    "clearcoatRoughnessTexture": {"index": 1},
                                                    "clearcoatNormalTexture": {"index": 2}},
                        "KHR_materials_ior": {"ior": 1.4},
                        "KHR_materials_emissive_strength": {"emissiveStrength": 4}}},
        {"name": "textured", "alphaMode": "MASK",
         "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1],
                                  "baseColorTexture": {"index": 0},
                                  "metallicRoughnessTexture": {"index": 1}},
         "normalTexture": {"index": 2}},
        {"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.6,
         "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.7],
                                  "baseColorTexture": {"index": 3, "extensions":
                                      {"KHR_texture_transform": {"offset": [0.5, 0],
                                          "rotation": 1.5707963, "scale": [2, 3]}}}},
         "extensions": {"KHR_materials_sheen": {"sheenColorFactor": [1, 0, 0]}},
         "extras": {"extensions": {"not_one": {}}}},
        {"name": "veil", "alphaMode": "BLEND",
         "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.25]}}],
      "textures": [{"source": 0}, {"source": 1}, {"source": 2}, {"source": 3}],
      "images": [{"uri": "base.png"}, {"uri": "mr.png"},
                 {"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAIAAAD91JpzAAAAEElEQVR4nGNoaPgPRAwQCgA19gf9SShDzAAAAABJRU5ErkJggg=="},
                 {"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAABCAYAAAD0In+KAAAAD0lEQVR4nGM4YWT0H4gZABHoA1ggLQeIAAAAAElFTkSuQmCC"}],
      )" + kTexturedTriangle + "}");
    auto p = dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "objects": [{"type": "mesh", "file": "two.gltf", "materials": "file"}]})");
    static std::vector<std::string> warnings;
    warnings.clear();
    LoadOptions options;
    options.warn = [](const std::string& w) { warnings.push_back(w); };
    Scene s = load_scene(p, options);
    auto material_of = [&](const char* name) -> const Material& {
        for (const Mesh& m : s.meshes)
            if (m.name == std::string("two.gltf:") + name) return s.materials[m.material];
        ADD_FAILURE() << "no mesh for material " << name;
        return s.materials[0];
    };
    const Material& coated = material_of("coated");
    EXPECT_EQ(coated.kind, MaterialKind::MetallicRoughness);
    EXPECT_EQ(s.textures[coated.albedo].color, Color(0.8f, 0.6f, 0.4f));
    EXPECT_FLOAT_EQ(coated.metallic, 0.3f);
    EXPECT_FLOAT_EQ(coated.roughness, 0.6f);
    EXPECT_FLOAT_EQ(coated.ior, 1.4f);
    EXPECT_FLOAT_EQ(coated.transmission, 0.4f);
    EXPECT_FLOAT_EQ(coated.clearcoat, 0.7f);
    EXPECT_FLOAT_EQ(coated.clearcoat_roughness, 0.2f);
    // The coat's textures: red times the factor, green times the roughness (the coat's alpha
    // its square), where the vertex's BSDF is made; so the transmission's red.
    ASSERT_NE(coated.clearcoat_map, kNone);
    ASSERT_NE(coated.clearcoat_roughness_map, kNone);
    ASSERT_NE(coated.clearcoat_normal_map, kNone);
    ASSERT_NE(coated.transmission_map, kNone);
    BsdfParams b;
    b.transmission = coated.transmission;
    metallic_roughness_at(s, coated, TexturePoint{{0.5f, 0.5f}, {}}, &b);
    EXPECT_FLOAT_EQ(b.transmission, 0.0f);                // mr.png's red is 0
    EXPECT_FLOAT_EQ(b.clearcoat, 0.7f);                   // base.png is white
    const float coat_roughness = 0.2f * 188.0f / 255.0f;  // mr.png's green, raw
    EXPECT_NEAR(b.clearcoat_alpha, coat_roughness * coat_roughness, 1e-6f);
    ASSERT_TRUE(coated.is_emissive());
    EXPECT_EQ(s.textures[coated.emission].color, Color(4.0f, 2.0f, 0.0f));  // strength 4
    EXPECT_TRUE(coated.two_sided);

    const Material& textured = material_of("textured");
    EXPECT_EQ(textured.kind, MaterialKind::MetallicRoughness);
    EXPECT_FLOAT_EQ(textured.ior, 1.5f);  // glTF's default
    EXPECT_FALSE(textured.is_emissive());
    const Texture& albedo = s.textures[textured.albedo];
    ASSERT_EQ(albedo.kind, TextureKind::Image);
    EXPECT_EQ(albedo.factor, Color(0.5f));
    EXPECT_EQ(eval_texture(s, textured.albedo, {0.5f, 0.5f}, {}), Color(0.5f));
    ASSERT_NE(textured.metallic_roughness, kNone);
    const Color t = eval_texture(s, textured.metallic_roughness, {0.5f, 0.5f}, {});
    // write_image stored 0.5 as the sRGB byte 188; read raw, that byte is not decoded back.
    EXPECT_NEAR(t.y, 188.0f / 255.0f, 1e-6f);
    EXPECT_EQ(t.z, 1.0f);
    // The normal texture is a data URI: decoded from memory, raw (128, 128, 255).
    ASSERT_NE(textured.normal_map, kNone);
    const Color n = eval_texture(s, textured.normal_map, {0.5f, 0.5f}, {});
    EXPECT_NEAR(n.x, 128.0f / 255.0f, 1e-6f);
    EXPECT_NEAR(n.z, 1.0f, 1e-6f);
    auto warned = [&](const std::string& part) {
        return std::any_of(warnings.begin(), warnings.end(),
                           [&](const std::string& w) { return w.find(part) != std::string::npos; });
    };
    // MASK over a base colour texture without alpha: solid wherever alpha 1 >= 0.5.
    ASSERT_NE(textured.opacity, kNone);
    EXPECT_EQ(eval_texture(s, textured.opacity, {0.3f, 0.6f}, {}), Color(1.0f));
    // MASK at 0.6 over texels of alpha 1 and 0 (left, right) times 0.7: solid left, a hole right,
    // through KHR_texture_transform: in glTF's uv (v down) u' = 0.5 + 3 v, v' = -2 u (a quarter
    // turn of the scaled uv, then the offset), so in the mesh's (v up, as Assimp flips it)
    // u' = 3.5 - 3 v, v' = 1 + 2 u: u' = 2.75 at v = 0.25 (the right texel), 2.25 at v = 5/12
    // (the left one).
    const Material& leaf = material_of("leaf");
    ASSERT_NE(leaf.opacity, kNone);
    const Texture& moved = s.textures[leaf.albedo];
    const float expected_uv[2][3] = {{0, -3, 3.5f}, {2, 0, 1}};
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(moved.uv[r][c], expected_uv[r][c], 1e-6f);
    EXPECT_EQ(eval_texture(s, leaf.opacity, {0.5f, 5.0f / 12.0f}, {}), Color(1.0f));
    EXPECT_EQ(eval_texture(s, leaf.opacity, {0.5f, 0.25f}, {}), Color(0.0f));
    // The alpha is coverage, not colour: the base colour keeps its texels' RGB.
    EXPECT_NEAR(eval_texture(s, leaf.albedo, {0.5f, 0.25f}, {}).x, 0.578f, 1e-3f);
    // BLEND: a quarter of the rays stop.
    const Material& veil = material_of("veil");
    ASSERT_NE(veil.opacity, kNone);
    EXPECT_EQ(s.textures[veil.opacity].color, Color(0.25f));
    // Every texture found its place (the coat over an emission too: it darkens the emission,
    // shading's emitted_radiance); the one warning is for the extensions not read (a
    // material's, a texture's; not what `extras` holds).
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_TRUE(warned("\"leaf\": ignored KHR_materials_sheen")) << warnings[0];
}

// A .glb holds its JSON in its first chunk: the emissive strength is read from there, and a
// container whose chunk overruns the file, a negative strength or a texture transform of a
// string, is refused with a reason.
// A glTF texture's sampler: wrapS and wrapT each its own wrap, magFilter NEAREST the nearest
// texel; a texture without a sampler repeats and is filtered bilinearly (glTF's default wrap).
TEST(MeshFiles, GltfSamplersSetEachTexturesWrapAndFilter) {
    TempDir dir;
    Image base(2, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) base.at(x, y) = Color(1.0f);
    write_image(dir.path() / "base.png", base);
    dir.write("one.gltf", R"({
      "asset": {"version": "2.0"},
      "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
      "materials": [{"name": "sampled",
         "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                  "metallicRoughnessTexture": {"index": 1}},
         "emissiveTexture": {"index": 2}, "emissiveFactor": [1, 1, 1]}],
      "samplers": [{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728},
                   {"wrapS": 33648, "wrapT": 10497, "magFilter": 9729}],
      "textures": [{"source": 0, "sampler": 0}, {"source": 0, "sampler": 1}, {"source": 0}],
      "images": [{"uri": "base.png"}],
      )" + kTexturedTriangle + "}");
    auto p = dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "objects": [{"type": "mesh", "file": "one.gltf", "materials": "file"}]})");
    Scene s = load_scene(p);
    ASSERT_EQ(s.meshes.size(), 1u);
    const Material& m = s.materials[s.meshes[0].material];
    ASSERT_NE(m.albedo, kNone);
    ASSERT_NE(m.metallic_roughness, kNone);
    ASSERT_NE(m.emission, kNone);
    const Texture& clamped = s.textures[m.albedo];
    EXPECT_EQ(clamped.wrap_u, TextureWrap::Clamp);
    EXPECT_EQ(clamped.wrap_v, TextureWrap::Mirror);
    EXPECT_EQ(clamped.filter, TextureFilter::Nearest);
    const Texture& mirrored = s.textures[m.metallic_roughness];
    EXPECT_EQ(mirrored.wrap_u, TextureWrap::Mirror);
    EXPECT_EQ(mirrored.wrap_v, TextureWrap::Repeat);
    EXPECT_EQ(mirrored.filter, TextureFilter::Bilinear);
    const Texture& plain = s.textures[m.emission];
    EXPECT_EQ(plain.wrap_u, TextureWrap::Repeat);
    EXPECT_EQ(plain.wrap_v, TextureWrap::Repeat);
    EXPECT_EQ(plain.filter, TextureFilter::Bilinear);
}

TEST(MeshFiles, GlbEmissiveStrengthAndBrokenContainers) {
    TempDir dir;
    // The positions of one triangle, as the BIN chunk of a .glb or base64 in a .gltf.
    const float tri[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::string bin(reinterpret_cast<const char*>(tri), sizeof tri);
    auto glb = [&](std::string json) {
        const std::string uri = R"(, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA")";
        json.erase(json.find(uri), uri.size());  // the buffer is the BIN chunk
        while (json.size() % 4) json += ' ';
        std::string out = "glTF";
        auto u32 = [&](uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
        u32(2);
        u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
        u32(uint32_t(json.size()));
        u32(0x4E4F534Au);  // "JSON"
        out += json;
        u32(uint32_t(bin.size()));
        u32(0x004E4942u);  // "BIN"
        return out + bin;
    };
    auto json = [](const std::string& strength) {
        return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
          "nodes": [{"mesh": 0}], "extensionsUsed": ["KHR_materials_emissive_strength"],
          "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
          "materials": [{"name": "lamp", "emissiveFactor": [1, 1, 1], "extensions":
            {"KHR_materials_emissive_strength": {"emissiveStrength": )" + strength + R"(}}}],
          "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
          "bufferViews": [{"buffer": 0, "byteLength": 36}],
          "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                         "min": [0, 0, 0], "max": [1, 1, 0]}]})";
    };
    auto scene = [&](const char* file) {
        return dir.write("s.json", std::string(R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
            "objects": [{"type": "mesh", "file": ")") + file + R"(", "materials": "file"}]})");
    };
    dir.write("lamp.glb", glb(json("2.5")));
    Scene s = load_scene(scene("lamp.glb"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Material& lamp = s.materials[s.meshes[0].material];
    ASSERT_TRUE(lamp.is_emissive());
    EXPECT_EQ(s.textures[lamp.emission].color, Color(2.5f));

    auto error = [&](const char* file) -> std::string {
        try {
            load_scene(scene(file));
        } catch (const SceneError& e) {
            return e.what();
        }
        return "";
    };
    dir.write("negative.gltf", json("-1"));
    EXPECT_NE(error("negative.gltf").find("negative.gltf"), std::string::npos);
    EXPECT_NE(error("negative.gltf").find("emissiveStrength must be a number in [0, 1e6], got -1"),
              std::string::npos)
        << error("negative.gltf");
    std::string overrun = glb(json("1"));
    overrun[12] = char(0xF0);  // the JSON chunk claims more bytes than the file has
    dir.write("overrun.glb", overrun);
    EXPECT_NE(error("overrun.glb").find("overrun.glb"), std::string::npos) << error("overrun.glb");
    EXPECT_NE(error("overrun.glb"), "");
    // A texture transform that is not numbers, named by its JSON pointer.
    std::string moved = json("1");
    moved.replace(moved.find("\"emissiveFactor\""), 0,
                  R"("emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform":
                       {"scale": [1, "x"]}}}, )");
    moved.replace(
        moved.find("\"buffers\""), 0,
        R"("textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAIAAAD91JpzAAAAEElEQVR4nGNoaPgPRAwQCgA19gf9SShDzAAAAABJRU5ErkJggg=="}], )");
    dir.write("moved.gltf", moved);
    EXPECT_NE(error("moved.gltf")
                  .find("/materials/0/emissiveTexture/extensions/"
                        "KHR_texture_transform/scale/1: expected a number"),
              std::string::npos)
        << error("moved.gltf");
}

// Materials from an OBJ's MTL file: each key maps as docs/scene-format.md says, one scene mesh
// per material, and what cannot be mapped is a warning naming the material.
TEST(MeshFiles, ObjMaterialsMapFromTheMtl) {
    TempDir dir;
    std::string obj = "mtllib m.mtl\n";
    const char* names[] = {"paint", "lamp", "glass", "steel", "plastic", "ghost"};
    for (int k = 0; k < 6; ++k) {  // one triangle per material, side by side
        const float x = 2.0f * k;
        obj += "v " + std::to_string(x) + " 0 0\nv " + std::to_string(x + 1) + " 0 0\nv " +
               std::to_string(x) + " 1 0\n";
        obj += std::string("usemtl ") + names[k] + "\nf -3 -2 -1\n";
    }
    dir.write("m.obj", obj);
    dir.write("m.mtl",
              "newmtl paint\nKd 0.2 0.4 0.6\nillum 2\n"
              "newmtl lamp\nKd 0.78 0.78 0.78\nKe 17 12 4\n"
              "newmtl glass\nNi 1.33\nillum 7\nKd 0 0 0\n"
              "newmtl steel\nKd 0 0 0\nKs 0.9 0.8 0.7\nNs 98\nillum 3\n"
              "newmtl plastic\nKd 0.5 0.5 0.5\nKs 0.3 0.3 0.3\nd 0.5\n"
              "newmtl ghost\nKd 0 0 0\n");
    auto p = dir.write("s.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "objects": [{"type": "mesh", "file": "m.obj", "materials": "file"}]})");
    static std::vector<std::string> warnings;
    warnings.clear();
    LoadOptions options;
    options.warn = [](const std::string& w) { warnings.push_back(w); };
    Scene s = load_scene(p, options);

    ASSERT_EQ(s.meshes.size(), 6u);
    auto material_of = [&](const char* name) -> const Material& {
        for (const Mesh& m : s.meshes)
            if (m.name == std::string("m.obj:") + name) return s.materials[m.material];
        ADD_FAILURE() << "no mesh for material " << name;
        return s.materials[0];
    };
    auto color = [&](TextureId t) { return s.textures[t].color; };
    const Material& paint = material_of("paint");
    EXPECT_EQ(paint.kind, MaterialKind::Lambertian);
    EXPECT_EQ(color(paint.albedo), Color(0.2f, 0.4f, 0.6f));
    const Material& lamp = material_of("lamp");
    EXPECT_EQ(lamp.kind, MaterialKind::DiffuseLight);
    EXPECT_EQ(color(lamp.emission), Color(17, 12, 4));
    EXPECT_FALSE(lamp.two_sided);
    EXPECT_EQ(color(lamp.albedo), Color(0.78f));  // it reflects, too
    const Material& glass = material_of("glass");
    EXPECT_EQ(glass.kind, MaterialKind::Dielectric);
    EXPECT_FLOAT_EQ(glass.ior, 1.33f);
    const Material& steel = material_of("steel");
    EXPECT_EQ(steel.kind, MaterialKind::Metal);
    EXPECT_EQ(color(steel.albedo), Color(0.9f, 0.8f, 0.7f));
    // roughness^2 = alpha = sqrt(2 / (Ns + 2)) = sqrt(0.02)
    EXPECT_NEAR(steel.roughness * steel.roughness, std::sqrt(0.02f), 1e-6f);
    EXPECT_EQ(material_of("plastic").kind, MaterialKind::Lambertian);

    auto warned = [&](const std::string& part) {
        return std::any_of(warnings.begin(), warnings.end(),
                           [&](const std::string& w) { return w.find(part) != std::string::npos; });
    };
    EXPECT_TRUE(
        warned("material \"plastic\": ignored Ks (no diffuse + glossy material), d "
               "(transparency)"));
    EXPECT_TRUE(warned("material \"ghost\": no Kd, Ks or Ke; rendered black"));
    EXPECT_FALSE(warned("\"paint\""));
    EXPECT_FALSE(warned("\"lamp\""));

    // "material" and "materials" together are refused, naming the place.
    auto both =
        dir.write("both.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
        "materials": {"m": {"type": "lambertian", "albedo": 0.5}},
        "objects": [{"type": "mesh", "file": "m.obj", "materials": "file", "material": "m"}]})");
    try {
        load_scene(both, options);
        ADD_FAILURE() << "expected an error";
    } catch (const SceneError& e) {
        EXPECT_NE(std::string(e.what()).find("/objects/0/material"), std::string::npos) << e.what();
    }
}
