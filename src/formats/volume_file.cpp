#include "formats/volume_file.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>

#include "files/input_file.h"

namespace wavetrace {
namespace {

constexpr size_t kGridHeaderBytes = 48;
constexpr int32_t kGridFloat32 = 1;

[[noreturn]] void bad_grid(const std::string& message) {
    throw std::runtime_error(message);
}

int32_t grid_int_at(const std::string& bytes, size_t at) {
    int32_t v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    return v;  // little-endian, as every platform we build for
}

}  // namespace

VolumeGrid read_volume_file(const std::filesystem::path& path, Aabb* bounds) {
    check_input_file(path, kMaxImageFileBytes, "volume grids");
    const std::string bytes = read_input_file(path);
    if (bytes.size() < kGridHeaderBytes)
        bad_grid("is " + std::to_string(bytes.size()) + " bytes, shorter than the 48-byte header");
    if (bytes.compare(0, 3, "VOL") != 0)
        bad_grid("does not start with \"VOL\" (not a volume grid)");
    if (bytes[3] != 3)
        bad_grid("has version " + std::to_string(static_cast<unsigned char>(bytes[3])) +
                 " at byte 3; only version 3 is known");
    if (const int32_t encoding = grid_int_at(bytes, 4); encoding != kGridFloat32)
        bad_grid("has encoding " + std::to_string(encoding) +
                 " at byte 4; only 1 (32-bit floats) is read");
    VolumeGrid g;
    g.path = path.string();
    static const char* kAxis[] = {"x", "y", "z"};
    uint64_t voxels = 1;
    for (int a = 0; a < 3; ++a) {
        g.res[a] = grid_int_at(bytes, 8 + 4 * a);
        if (g.res[a] < 1)
            bad_grid("has " + std::string(kAxis[a]) + " resolution " + std::to_string(g.res[a]) +
                     " at byte " + std::to_string(8 + 4 * a) + "; it must be at least 1");
        voxels *= static_cast<uint64_t>(g.res[a]);  // each < 2^31: no overflow in 64 bits
        if (voxels > bytes.size()) break;           // the size check below fails
    }
    g.channels = grid_int_at(bytes, 20);
    if (g.channels != 1 && g.channels != 3)
        bad_grid("has " + std::to_string(g.channels) +
                 " channels at byte 20; a volume grid here holds 1 (grey) or 3 (RGB)");
    const uint64_t count = voxels * static_cast<uint64_t>(g.channels);
    const uint64_t payload = bytes.size() - kGridHeaderBytes;
    if (voxels > bytes.size() || count * 4 != payload)
        bad_grid("has " + std::to_string(payload) + " bytes of values; its header (" +
                 std::to_string(g.res[0]) + " x " + std::to_string(g.res[1]) + " x " +
                 std::to_string(g.res[2]) + " voxels, " + std::to_string(g.channels) +
                 " channels) claims " +
                 (voxels > bytes.size() ? "far more" : std::to_string(count * 4)));
    if (bounds) {
        float b[6];
        std::memcpy(b, bytes.data() + 24, sizeof b);
        *bounds = Aabb{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    }
    g.values.resize(count);
    std::memcpy(g.values.data(), bytes.data() + kGridHeaderBytes, payload);
    for (size_t i = 0; i < g.values.size(); ++i)
        if (!(g.values[i] >= 0.0f) || !std::isfinite(g.values[i])) {
            const size_t voxel = i / g.channels;
            const size_t x = voxel % g.res[0], y = voxel / g.res[0] % g.res[1],
                         z = voxel / g.res[0] / g.res[1];
            bad_grid("holds " + std::to_string(g.values[i]) + " at voxel (" + std::to_string(x) +
                     ", " + std::to_string(y) + ", " + std::to_string(z) + ") channel " +
                     std::to_string(i % g.channels) + "; values must be finite and >= 0");
        }
    return g;
}

}  // namespace wavetrace
