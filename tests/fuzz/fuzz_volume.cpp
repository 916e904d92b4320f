// libFuzzer target: a Mitsuba .vol file through read_volume_file (our own reader), and a grid
// it accepts through the lookups and the optical-depth walk of a medium over it.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "formats/volume_file.h"
#include "media/grid_track.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path file = fs::temp_directory_path() /
                                 ("wavetrace-fuzz-volume-" + std::to_string(::getpid()) + ".vol");
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        const wavetrace::VolumeGrid g = wavetrace::read_volume_file(file);
        (void)g.lookup({0.3f, 0.5f, 0.7f});
        (void)g.lookup({-2.0f, 5.0f, 0.5f});
        const wavetrace::Color scale{1.0f, 2.0f, 0.5f};
        const wavetrace::Vec3 dir = normalize(wavetrace::Vec3{1.0f, 0.3f, -0.2f});
        const wavetrace::GridReach all =
            wavetrace::grid_reach(g, scale, {-0.5f, 0.4f, 0.6f}, dir, 4.0f, 0, 1e30f);
        (void)wavetrace::grid_reach(g, scale, {-0.5f, 0.4f, 0.6f}, dir, 4.0f, 1,
                                    0.5f * all.depth.y);
    } catch (const std::runtime_error&) {
    }
    fs::remove(file);
    return 0;
}
