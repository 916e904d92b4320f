#include "formats/serialized_mesh.h"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "files/input_file.h"

namespace wavetrace {
namespace {

constexpr uint16_t kMagic = 0x041C;
constexpr uint32_t kHasNormals = 0x0001, kHasUvs = 0x0002, kHasColors = 0x0008,
                   kFaceNormals = 0x0010, kDouble = 0x2000;
// DEFLATE's largest ratio (a run of one byte: 258 bytes per 2 bits, about 1032:1), rounded up.
constexpr uint64_t kMaxInflation = 1100;
constexpr size_t kMaxNameBytes = 4096;

[[noreturn]] void fail(const std::string& message) { throw std::runtime_error(message); }

template <class T>
T little(const std::string& bytes, uint64_t at) {
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;  // the format is little-endian, as every platform we build for
}

// The shape's zlib stream, read piece by piece into what the caller allocated.
class Inflater {
  public:
    Inflater(const std::string& bytes, uint64_t from) {
        z_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data() + from));
        z_.avail_in = static_cast<uInt>(bytes.size() - from);
        if (inflateInit(&z_) != Z_OK) fail("cannot start decompressing");
    }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;
    ~Inflater() { inflateEnd(&z_); }

    void read(void* out, size_t n, const char* what) {
        auto* at = static_cast<Bytef*>(out);
        while (n > 0) {
            const uInt chunk = static_cast<uInt>(std::min<size_t>(n, 1u << 30));
            z_.next_out = at;
            z_.avail_out = chunk;
            const int status = inflate(&z_, Z_NO_FLUSH);
            const size_t got = chunk - z_.avail_out;
            at += got;
            n -= got;
            if (n > 0 && (status == Z_STREAM_END || (status == Z_BUF_ERROR && got == 0)))
                fail(std::string("the compressed data ends inside the ") + what);
            if (status != Z_OK && status != Z_STREAM_END && status != Z_BUF_ERROR)
                fail(std::string("the compressed data is damaged (") +
                     (z_.msg ? z_.msg : "zlib error " + std::to_string(status)) + ") in the " +
                     what);
        }
    }
    template <class T>
    T value(const char* what) {
        T v;
        read(&v, sizeof v, what);
        return v;
    }

  private:
    z_stream z_{};
};

// `count` vectors of `dim` floats or doubles, as floats.
std::vector<float> read_reals(Inflater& in, uint64_t count, int dim, bool dbl, const char* what) {
    std::vector<float> out(count * dim);
    if (!dbl) {
        in.read(out.data(), out.size() * sizeof(float), what);
        return out;
    }
    std::vector<double> d(count * dim);
    in.read(d.data(), d.size() * sizeof(double), what);
    for (size_t i = 0; i < d.size(); ++i) out[i] = static_cast<float>(d[i]);
    return out;
}

}  // namespace

MeshFile read_serialized_mesh(const std::filesystem::path& path, uint32_t shape_index) {
    check_input_file(path, kMaxMeshFileBytes, "meshes");
    const std::string bytes = read_input_file(path);
    if (bytes.size() < 4 || little<uint16_t>(bytes, 0) != kMagic)
        fail("not a Mitsuba .serialized file (its first two bytes are not 0x041C)");
    const uint16_t version = little<uint16_t>(bytes, 2);
    if (version != 3 && version != 4)
        fail("version " + std::to_string(version) + " (versions 3 and 4 are read)");

    // Where the shape starts: 0, or what the dictionary at the end of the file says.
    uint64_t start = 0;
    if (shape_index > 0) {
        if (bytes.size() < 8) fail("no dictionary of shapes at the end of the file");
        const uint32_t count = little<uint32_t>(bytes, bytes.size() - 4);
        const uint64_t entry = version == 4 ? 8 : 4;
        if (count > (bytes.size() - 4) / entry)
            fail("the dictionary claims " + std::to_string(count) +
                 " shapes, more than the file holds");
        if (shape_index >= count)
            fail("shape_index " + std::to_string(shape_index) + " of a file of " +
                 std::to_string(count) + " shapes");
        const uint64_t at = bytes.size() - 4 - entry * (count - shape_index);
        start = version == 4 ? little<uint64_t>(bytes, at) : little<uint32_t>(bytes, at);
        if (start > bytes.size() - 4 || little<uint16_t>(bytes, start) != kMagic ||
            little<uint16_t>(bytes, start + 2) != version)
            fail("the dictionary's offset " + std::to_string(start) + " of shape " +
                 std::to_string(shape_index) + " is not the start of a shape");
    }

    Inflater in(bytes, start + 4);
    const uint32_t flags = in.value<uint32_t>("flags");
    std::string name;
    if (version == 4) {
        for (char c; (c = in.value<char>("shape's name")) != '\0';) {
            if (name.size() == kMaxNameBytes)
                fail("a shape name longer than " + std::to_string(kMaxNameBytes) + " bytes");
            name += c;
        }
    }
    const uint64_t vertices = in.value<uint64_t>("vertex count");
    const uint64_t triangles = in.value<uint64_t>("triangle count");
    // What the counts need, against what the compressed bytes can expand to.
    const bool dbl = (flags & kDouble) != 0;
    const uint64_t real = dbl ? 8 : 4;
    const int dims = 3 + ((flags & kHasNormals) ? 3 : 0) + ((flags & kHasUvs) ? 2 : 0) +
                     ((flags & kHasColors) ? 3 : 0);
    const uint64_t room = kMaxInflation * (bytes.size() - start);
    if (vertices > room / (real * dims) || triangles > room / 12 ||
        vertices * real * dims + triangles * 12 > room)
        fail("it claims " + std::to_string(vertices) + " vertices and " +
             std::to_string(triangles) + " triangles, more than its " +
             std::to_string(bytes.size() - start) + " bytes can hold");
    if (vertices > 0xFFFFFFFFu) fail("more than 2^32 vertices");

    MeshFile mesh;
    const std::vector<float> p = read_reals(in, vertices, 3, dbl, "positions");
    mesh.positions.resize(vertices);
    for (size_t i = 0; i < vertices; ++i) mesh.positions[i] = {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    if (flags & kHasNormals) {
        const std::vector<float> n = read_reals(in, vertices, 3, dbl, "normals");
        if (!(flags & kFaceNormals)) {
            mesh.normals.resize(vertices);
            for (size_t i = 0; i < vertices; ++i)
                mesh.normals[i] = {n[3 * i], n[3 * i + 1], n[3 * i + 2]};
        }
    }
    if (flags & kHasUvs) {
        const std::vector<float> t = read_reals(in, vertices, 2, dbl, "uvs");
        mesh.uvs.resize(vertices);
        for (size_t i = 0; i < vertices; ++i) mesh.uvs[i] = {t[2 * i], t[2 * i + 1]};
    }
    if (flags & kHasColors) (void)read_reals(in, vertices, 3, dbl, "vertex colours");
    mesh.indices.resize(triangles * 3);
    in.read(mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t), "triangles");
    for (size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= vertices)
            fail("triangle " + std::to_string(i / 3) + " uses vertex " +
                 std::to_string(mesh.indices[i]) + " of " + std::to_string(vertices));
    if (mesh.indices.empty()) fail("the shape holds no triangles");
    FileMaterial material;
    material.name = name;
    mesh.materials.push_back(material);
    mesh.parts.push_back({0, static_cast<size_t>(triangles), 0});
    return mesh;
}

}  // namespace wavetrace
