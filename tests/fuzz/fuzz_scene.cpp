// libFuzzer target: a scene file, through the whole loader and the BVH build. The input is
// written as x.json into a private folder that also holds small meshes and textures under
// the names the shipped scenes use (meshes/bunny.ply, textures/*.png, ...), so that mutated
// scenes exercise the mesh and image paths too. Errors (SceneError, ImageError) are the
// expected outcome of bad input; a crash, a hang, a leak or a sanitizer report is a finding.
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
    fs::path dir =
        fs::temp_directory_path() / ("wavetrace-fuzz-scene-" + std::to_string(::getpid()));
    fs::create_directories(dir / "meshes");
    fs::create_directories(dir / "textures");
    const fs::path data = WAVETRACE_FUZZ_DATA_DIR;
    // Small stand-ins for the shipped scenes' big meshes, and the real (small) textures.
    for (const char* name : {"bunny.ply", "dragon_100k.obj"})
        fs::copy_file(data / (std::string("standin") + fs::path(name).extension().string()),
                      dir / "meshes" / name, fs::copy_options::overwrite_existing);
    for (const auto& e : fs::directory_iterator(fs::path(WAVETRACE_SCENES_DIR) / "textures"))
        fs::copy_file(e.path(), dir / "textures" / e.path().filename(),
                      fs::copy_options::overwrite_existing);
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path dir = setup();
    load_input(dir / "x.json", data, size);
    return 0;
}
