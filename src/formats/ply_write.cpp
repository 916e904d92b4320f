#include "formats/ply_write.h"

#include <bit>
#include <cstring>
#include <string>

namespace wavetrace {

static_assert(std::endian::native == std::endian::little, "PLY bodies are written as in memory");

std::vector<unsigned char> encode_ply(const std::vector<Point3>& positions,
                                      const std::vector<Normal3>& normals,
                                      const std::vector<Vec2>& uvs,
                                      const std::vector<uint32_t>& indices) {
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment written by wavetrace\n";
    header += "element vertex " + std::to_string(positions.size()) + "\n";
    header += "property float x\nproperty float y\nproperty float z\n";
    if (!normals.empty()) header += "property float nx\nproperty float ny\nproperty float nz\n";
    if (!uvs.empty()) header += "property float u\nproperty float v\n";
    header += "element face " + std::to_string(indices.size() / 3) + "\n";
    header += "property list uchar int vertex_indices\nend_header\n";
    std::vector<unsigned char> out(header.begin(), header.end());
    auto put = [&out](const void* data, size_t bytes) {
        const auto* b = static_cast<const unsigned char*>(data);
        out.insert(out.end(), b, b + bytes);
    };
    const size_t floats = 3 + (normals.empty() ? 0 : 3) + (uvs.empty() ? 0 : 2);
    out.reserve(out.size() + positions.size() * floats * 4 + indices.size() / 3 * 13);
    for (size_t i = 0; i < positions.size(); ++i) {
        put(&positions[i].x, 4), put(&positions[i].y, 4), put(&positions[i].z, 4);
        if (!normals.empty()) put(&normals[i].x, 4), put(&normals[i].y, 4), put(&normals[i].z, 4);
        if (!uvs.empty()) put(&uvs[i].x, 4), put(&uvs[i].y, 4);
    }
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const unsigned char three = 3;
        put(&three, 1);
        for (int k = 0; k < 3; ++k) {
            const int32_t v = static_cast<int32_t>(indices[t + k]);
            put(&v, 4);
        }
    }
    return out;
}

}  // namespace wavetrace
