#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "formats/mesh_data.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Reads a mesh file: PLY with formats/ply_mesh.h, OBJ (+MTL), glTF 2.0 and the other formats
// Assimp knows through Assimp. Polygons are
// triangulated (fans of the file's own faces), points and lines dropped; materials are read as
// the file states them. Every file it reads goes through MeshIO (loaders/mesh_io.h): regular,
// within the size limit, inside the mesh's folder and `asset_root` (if not empty). Throws
// std::runtime_error with a message that does not repeat the path (but names any other file).
MeshFile read_mesh_file(const std::filesystem::path& path,
                        const std::filesystem::path& asset_root = {});

// Area-weighted vertex normals (each face adds its unnormalized cross product).
std::vector<Normal3> smooth_normals(const std::vector<Point3>& positions,
                                    const std::vector<uint32_t>& indices);

}  // namespace wavetrace
