// pbrt-v4 scene files translated into our JSON scene document, which the JSON loader then
// builds: one scene model, and `convert` writes what a render reads. docs/scene-format.md,
// "pbrt-v4 files", says what maps to what.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// A triangle mesh written out in the scene file (trianglemesh, bilinearmesh, disk,
// loopsubdiv), in the shape's own coordinates; its triangles wind counter-clockwise about
// the side pbrt's surface normal points to.
struct PbrtMesh {
    std::vector<Point3> positions;
    std::vector<Normal3> normals;  // empty, or one per position
    std::vector<Vec2> uvs;         // empty, or one per position
    std::vector<uint32_t> indices;
};

struct PbrtDocument {
    nlohmann::json scene;  // our JSON scene; file names relative to the pbrt file's folder
    // For each entry of scene["objects"]: the directive it came from ("a.pbrt:12").
    std::vector<std::string> object_places;
    // For each entry of scene["lights"]: the directive it came from; the background's, if any.
    std::vector<std::string> light_places;
    std::string background_place;
    // The meshes written out in the file, by the "file" name their mesh objects give
    // ("@mesh/3": never a real file); the loader takes them from here, `convert` writes them.
    std::map<std::string, PbrtMesh> meshes;
};

// Reads `path` with its includes. Throws SceneError naming the file and line on bad input;
// `warn` gets, for each directive or parameter it cannot represent, a message naming its place
// ("a.pbrt:12: warning: Shape \"curve\" is not supported; skipped"). Every file it reads
// (includes, spectra) must lie inside `asset_root`, if not empty.
PbrtDocument translate_pbrt(const std::filesystem::path& path,
                            const std::function<void(const std::string&)>& warn,
                            const std::filesystem::path& asset_root = {});

}  // namespace wavetrace
