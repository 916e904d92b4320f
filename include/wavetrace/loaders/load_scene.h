// Reading a scene file into a Scene.
#pragma once

#include <filesystem>
#include <string>

#include "wavetrace/scene/scene.h"

namespace wavetrace {

struct LoadOptions {
    // Called with warnings (e.g. skipped degenerate triangles); default: print to stderr.
    void (*warn)(const std::string& message) = nullptr;
};

// Loads a JSON scene file (see docs/scene-format.md) and the meshes, textures and environment
// maps it names. Throws SceneError on bad input, naming the file and the place in it.
Scene load_scene(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace wavetrace
