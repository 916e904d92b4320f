// Reading a scene file into a Scene.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "wavetrace/scene/scene.h"

namespace wavetrace {

struct LoadOptions {
    // Called with warnings (e.g. skipped degenerate triangles); default: print to stderr.
    void (*warn)(const std::string& message) = nullptr;
    // A glTF scene: the camera to render through, by its name (or its node's); empty: the
    // first. A name the file does not hold is an error.
    std::string camera;
    // A Mitsuba XML scene: values for its $parameters (-D name=value), overriding <default>s.
    std::map<std::string, std::string> params;
};

// Loads a scene file and the meshes, textures and environment maps it names: our JSON
// (docs/scene-format.md), a Mitsuba 3 XML file (.xml), or a glTF 2.0 file (.gltf, .glb) as a
// whole scene with its camera and lights. Throws SceneError on bad input, naming the file and the place in it.
Scene load_scene(const std::filesystem::path& path, const LoadOptions& options = {});

// A scene file as our JSON scene (docs/scene-format.md): a Mitsuba XML file translated as
// load_scene() reads it, a JSON file as it is; file names are rewritten relative to
// `output_folder`, where the text is to be written. The scene is loaded first, so bad input
// throws as load_scene() does; loading the text gives the same Scene. glTF files are refused
// (their meshes are read directly, not through our JSON).
std::string convert_to_json(const std::filesystem::path& path,
                            const std::filesystem::path& output_folder,
                            const LoadOptions& options = {});

}  // namespace wavetrace
