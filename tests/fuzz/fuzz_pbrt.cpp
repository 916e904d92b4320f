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
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path dir = setup();
    const fs::path scene_file = dir / "x.pbrt";
    {
        std::ofstream out(scene_file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    wavetrace::LoadOptions options;
    options.warn = [](const std::string&) {};
    try {
        wavetrace::Scene scene = wavetrace::load_scene(scene_file, options);
        if (scene.primitive_count() <= 100000) (void)wavetrace::Bvh::build(scene);
    } catch (const wavetrace::SceneError&) {
    } catch (const wavetrace::ImageError&) {
    }
    return 0;
}
