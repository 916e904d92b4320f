// Reading a scene file into a Scene.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

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
    // Empty, or the folder every file the scene reads must lie in once symbolic links are
    // resolved (the scene file, its includes, meshes, what the meshes name, textures): a
    // render farm's confinement. A file outside is an error naming it.
    std::filesystem::path asset_root;
};

// Loads a scene file and the meshes, textures and environment maps it names: our JSON
// (docs/scene-format.md), a Mitsuba 3 XML file (.xml), a pbrt-v4 file (.pbrt), or a glTF 2.0
// file (.gltf, .glb) as a whole scene with its camera and lights. Throws SceneError on bad input, naming the file and the place in it.
Scene load_scene(const std::filesystem::path& path, const LoadOptions& options = {});

// Writes `output`: a scene file as our JSON scene (docs/scene-format.md) — a Mitsuba XML or
// pbrt file translated as load_scene() reads it, a JSON file as it is — its file names
// rewritten relative to `output`'s folder. A pbrt file's meshes written out in it
// (trianglemesh, bilinearmesh, disk, loopsubdiv) go into binary PLY files in the folder
// `STEM-meshes` beside `output` (created; files of the same names there are replaced). Loading
// `output` gives the same Scene. Every file is written whole or not at all; returns those
// written. Throws SceneError on bad input, as load_scene() does, before writing anything;
// std::runtime_error ("PATH: cannot write: REASON") if a write fails. glTF files are refused
// (their meshes are read directly, not through our JSON).
std::vector<std::filesystem::path> convert_scene(const std::filesystem::path& path,
                                                 const std::filesystem::path& output,
                                                 const LoadOptions& options = {});

}  // namespace wavetrace
