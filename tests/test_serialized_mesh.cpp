// Mitsuba's .serialized meshes: files written here by the format's documented layout (Mitsuba
// 3's plugin reference), read through a JSON scene and a Mitsuba XML scene; damaged, truncated
// and lying files are errors naming the file and the reason, never an allocation of what a
// header claims.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <string>
#include <vector>

#include "temp_dir.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

template <class T>
void put(std::string& s, T v) {
    s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

std::string deflated(const std::string& raw) {
    uLongf size = compressBound(raw.size());
    std::string out(size, '\0');
    EXPECT_EQ(compress(reinterpret_cast<Bytef*>(out.data()), &size,
                       reinterpret_cast<const Bytef*>(raw.data()), raw.size()),
              Z_OK);
    out.resize(size);
    return out;
}

struct Shape {
    uint32_t flags;
    std::string name;
    std::vector<double> positions, normals, uvs;
    std::vector<uint32_t> indices;
    uint64_t claimed_vertices = 0;  // 0: the true count
};

// One shape's bytes: the header, then its zlib stream.
std::string shape_bytes(const Shape& s, uint16_t version = 4) {
    std::string raw;
    put(raw, s.flags);
    if (version == 4) raw += s.name + '\0';
    const uint64_t vertices = s.positions.size() / 3;
    put(raw, s.claimed_vertices ? s.claimed_vertices : vertices);
    put<uint64_t>(raw, s.indices.size() / 3);
    const bool dbl = s.flags & 0x2000;
    for (const auto* a : {&s.positions, &s.normals, &s.uvs})
        for (double x : *a) dbl ? put(raw, x) : put(raw, static_cast<float>(x));
    for (uint32_t i : s.indices) put(raw, i);
    std::string out;
    put<uint16_t>(out, 0x041C);
    put<uint16_t>(out, version);
    return out + deflated(raw);
}

// Shapes back to back, then the dictionary of their offsets and their count.
std::string file_of(const std::vector<Shape>& shapes, uint16_t version = 4) {
    std::string out;
    std::vector<uint64_t> offsets;
    for (const Shape& s : shapes) {
        offsets.push_back(out.size());
        out += shape_bytes(s, version);
    }
    for (uint64_t o : offsets) version == 4 ? put(out, o) : put(out, static_cast<uint32_t>(o));
    put(out, static_cast<uint32_t>(shapes.size()));
    return out;
}

const Shape kTriangle{0x1000 | 0x0001 | 0x0002, "tri",
                      {0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 0, 0, 1, 0, 0, 1},
                      {0, 0, 1, 0, 0, 1}, {0, 1, 2}};
const Shape kQuad{0x2000, "quad", {0, 0, 5, 2, 0, 5, 2, 2, 5, 0, 2, 5}, {}, {}, {0, 1, 2, 0, 2, 3}};

std::string json_scene(const std::string& mesh_keys) {
    return R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
      "materials": {"w": {"type": "lambertian", "albedo": 0.5}},
      "objects": [{"type": "mesh", "material": "w", )" + mesh_keys + "}]}";
}

std::string error_of(const std::filesystem::path& p) {
    try {
        load_scene(p);
    } catch (const SceneError& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST(SerializedMeshes, EachShapeOfAFileLoadsByItsIndex) {
    for (uint16_t version : {uint16_t(3), uint16_t(4)}) {
        TempDir dir;
        dir.write("m.serialized", file_of({kTriangle, kQuad}, version));
        Scene first = load_scene(dir.write("a.json", json_scene(R"("file": "m.serialized")")));
        ASSERT_EQ(first.triangles.size(), 1u) << version;
        ASSERT_EQ(first.meshes.size(), 1u);
        EXPECT_TRUE(first.meshes[0].has_normals);  // the file's
        EXPECT_TRUE(first.meshes[0].has_uvs);
        EXPECT_NEAR(first.positions[first.triangles[0].v[1]].x, 1.0f, 1e-6f);
        Scene second = load_scene(
            dir.write("b.json", json_scene(R"("file": "m.serialized", "shape_index": 1)")));
        ASSERT_EQ(second.triangles.size(), 2u) << version;
        EXPECT_FALSE(second.meshes[0].has_normals);
        for (const Triangle& t : second.triangles)
            for (uint32_t v : t.v) EXPECT_NEAR(second.positions[v].z, 5.0f, 1e-6f);  // doubles
        // Mitsuba's own element, shape_index and face_normals included.
        Scene xml = load_scene(dir.write("c.xml", R"(<scene version="3.0.0">
  <sensor type="perspective"/>
  <shape type="serialized"><string name="filename" value="m.serialized"/>
    <integer name="shape_index" value="1"/></shape>
  <shape type="serialized"><string name="filename" value="m.serialized"/>
    <boolean name="face_normals" value="true"/></shape>
</scene>)"));
        ASSERT_EQ(xml.meshes.size(), 2u);
        EXPECT_EQ(xml.triangles.size(), 3u);
        EXPECT_FALSE(xml.meshes[1].has_normals);  // face_normals drops the file's
    }
}

TEST(SerializedMeshes, BadFilesAreErrorsWithTheReason) {
    TempDir dir;
    const std::string good = file_of({kTriangle, kQuad});
    struct Case {
        std::string bytes, keys, expect;
    };
    Shape lying = kTriangle;
    lying.claimed_vertices = uint64_t(1) << 40;  // 8 TB of positions in a ~100-byte file
    Shape bad_index = kTriangle;
    bad_index.indices = {0, 1, 7};
    std::string damaged = good;
    damaged[10] ^= 0x55;
    damaged[11] ^= 0x55;
    const std::vector<Case> cases = {
        {"PK\x03\x04" + good.substr(4), "", "not a Mitsuba .serialized file"},
        {std::string("\x1c\x04\x05\x00", 4) + good.substr(4), "", "version 5"},
        {file_of({lying}), "", "claims 1099511627776 vertices"},
        {file_of({bad_index}), "", "triangle 0 uses vertex 7 of 3"},
        {good.substr(0, 30), "", "the compressed data ends inside the"},
        {damaged, "", "the compressed data is damaged"},
        {good, R"(, "shape_index": 2)", "shape_index 2 of a file of 2 shapes"},
        {good.substr(0, good.size() - 4) + std::string("\xff\xff\xff\x0f", 4),
         R"(, "shape_index": 1)", "the dictionary claims 268435455 shapes"},
    };
    for (const Case& c : cases) {
        const auto mesh = dir.write("bad.serialized", c.bytes);
        const std::string e =
            error_of(dir.write("x.json", json_scene(R"("file": "bad.serialized")" + c.keys)));
        EXPECT_NE(e.find("/objects/0/file: cannot read mesh '" + mesh.string() + "'"),
                  std::string::npos)
            << e;
        EXPECT_NE(e.find(c.expect), std::string::npos) << c.expect << " -> " << e;
    }
    dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_NE(error_of(dir.write("y.json", json_scene(R"("file": "m.obj", "shape_index": 1)")))
                  .find("/objects/0/shape_index: only a Mitsuba .serialized file holds several"),
              std::string::npos);
}
