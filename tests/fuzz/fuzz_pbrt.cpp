// libFuzzer target: a pbrt-v4 scene file, through the tokenizer, the directives, the
// translation into our JSON and the JSON loader, then the BVH build. The input is written as
// x.pbrt into a private folder that also holds what the seeds name: part.pbrt to include, a
// small PLY mesh and a tiny image. Errors (SceneError, ImageError) are the expected outcome of
// bad input; a crash, a hang, a leak or a sanitizer report is a finding.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "load_input.h"
#include "wavetrace/wavetrace.h"

namespace fs = std::filesystem;

namespace {

fs::path setup() {
    fs::path dir = fs::temp_directory_path() / ("wavetrace-fuzz-pbrt-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path data = WAVETRACE_FUZZ_DATA_DIR;
    fs::copy_file(data / "standin.ply", dir / "mesh.ply", fs::copy_options::overwrite_existing);
    std::ofstream(dir / "part.pbrt") << "Shape \"sphere\" \"float radius\" 0.5\n";
    wavetrace::Image tiny(8, 4);
    for (wavetrace::Color& c : tiny.pixels) c = wavetrace::Color(0.5f, 0.6f, 0.7f);
    wavetrace::write_image(dir / "tex.png", tiny);
    // A square one, as an equal-area map of an infinite light must be.
    wavetrace::Image sky(4, 4);
    for (wavetrace::Color& c : sky.pixels) c = wavetrace::Color(0.9f, 0.8f, 0.7f);
    wavetrace::write_image(dir / "sky.png", sky);
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path dir = setup();
    load_input(dir / "x.pbrt", data, size);
    return 0;
}
