// Checks that run before Assimp reads a mesh file: the inputs on which Assimp 5.2's readers
// hang, crash or allocate without bound are refused here first, with a message that does not
// repeat the path (read_mesh_file adds it). Each guard says which reader fails and how.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

namespace wavetrace {

// An OFF file: vertex and face counts that a file of its size can hold.
void check_off(const std::filesystem::path& path);

// An OBJ file: at most this many material names, and polygons whose triangulation stays
// within this many steps (the sum of n^2 over polygons of n >= 5 vertices; about a second).
inline constexpr size_t kMaxObjMaterials = 4096;
inline constexpr uint64_t kMaxObjPolygonWork = uint64_t(1) << 26;
// And the material libraries it names (or its own name with .mtl): no statement before the
// first `newmtl`.
void check_obj(const std::filesystem::path& path);
void check_mtl(const std::filesystem::path& path);

}  // namespace wavetrace
