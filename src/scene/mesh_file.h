#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// A triangle mesh as read from a file: every mesh in the file merged, node transforms applied.
struct MeshFile {
    std::vector<Point3> positions;
    std::vector<Normal3> normals;   // empty, or one per position
    std::vector<Vec2> uvs;          // empty, or one per position
    std::vector<uint32_t> indices;  // three per triangle
};

// Reads OBJ (+MTL), PLY (ASCII or binary) or glTF 2.0 through Assimp. Polygons are
// triangulated (fans of the file's own faces), points and lines dropped. Throws
// std::runtime_error with a message that does not repeat the path.
MeshFile read_mesh_file(const std::filesystem::path& path);

// Area-weighted vertex normals (each face adds its unnormalized cross product).
std::vector<Normal3> smooth_normals(const std::vector<Point3>& positions,
                                    const std::vector<uint32_t>& indices);

}  // namespace wavetrace
