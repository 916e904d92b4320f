// libFuzzer target: a Mitsuba 3 XML scene file, through the XML reader, the translation into
// our JSON and the JSON loader, then the BVH build. The input is written as x.xml into a
// private folder that also holds what the seeds (Mitsuba 3's regression scenes, their <path>
// line dropped) name: fragments/ to include, small stand-ins for meshes/ and textures/.
// Errors (SceneError, ImageError) are the expected outcome of bad input; a crash, a hang, a
// leak or a sanitizer report is a finding.
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
    fs::path dir = fs::temp_directory_path() / ("wavetrace-fuzz-xml-" + std::to_string(::getpid()));
    fs::create_directories(dir / "meshes");
    fs::create_directories(dir / "textures");
    fs::create_directories(dir / "fragments");
    const fs::path data = WAVETRACE_FUZZ_DATA_DIR, scenes = WAVETRACE_SCENES_DIR;
    const auto copy = [](const fs::path& from, const fs::path& to) {
        fs::copy_file(from, to, fs::copy_options::overwrite_existing);
    };
    copy(data / "standin.obj", dir / "meshes" / "sphere.obj");
    copy(data / "standin.obj", dir / "meshes" / "rectangle.obj");
    copy(data / "standin.ply", dir / "meshes" / "mesh.ply");
    copy(scenes / "textures" / "leaf_mask.png", dir / "textures" / "leaf_mask.png");
    // Tiny images under the seeds' names: decoding must not dominate an execution.
    wavetrace::Image tiny(8, 4);
    for (wavetrace::Color& c : tiny.pixels) c = wavetrace::Color(0.5f, 0.6f, 0.7f);
    wavetrace::write_image(dir / "textures" / "museum.exr", tiny);
    wavetrace::write_image(dir / "textures" / "wood.jpg", tiny);
    const fs::path fragments = fs::path(WAVETRACE_REFERENCE_DIR) /
                               "mitsuba3/tests/scenes/bsdf_spheres/fragments";
    for (const char* f : {"sphere_grid.xml", "single_sphere.xml"})
        copy(fragments / f, dir / "fragments" / f);
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path dir = setup();
    load_input(dir / "x.xml", data, size);
    return 0;
}
