// Reading a scene file into a Scene.
#pragma once

#include <filesystem>
#include <string>

#include "wavetrace/scene/scene.h"

namespace wavetrace {

struct LoadOptions {
    // Called with warnings (e.g. skipped degenerate triangles); default: print to stderr.
    void (*warn)(const std::string& message) = nullptr;
    // A glTF scene: the camera to render through, by its name (or its node's); empty: the
    // first. A name the file does not hold is an error.
    std::string camera;
};

// Loads a scene file and the meshes, textures and environment maps it names: our JSON
// (docs/scene-format.md), or a glTF 2.0 file (.gltf, .glb) as a whole scene with its camera
// and lights. Throws SceneError on bad input, naming the file and the place in it.
Scene load_scene(const std::filesystem::path& path, const LoadOptions& options = {});

}  // namespace wavetrace
