// Mitsuba's .serialized meshes (Mitsuba 0.x–3 `serialized` shape), read by our own code: the
// format is small and documented in Mitsuba 3's plugin reference, and Assimp does not read it.
#pragma once

#include <cstdint>
#include <filesystem>

#include "formats/mesh_data.h"

namespace wavetrace {

// Reads shape `shape_index` of the file: a little-endian header (uint16 0x041C, uint16 version
// 3 or 4), then a zlib stream holding flags (uint32), the shape's name (version 4: a
// NUL-terminated string), vertex and triangle counts (uint64 each), positions, normals (flag
// 0x0001), uvs (0x0002) and colours (0x0008, skipped) as float (0x1000) or double (0x2000),
// and the triangles' uint32 indices. Several shapes lie back to back; the file ends with the
// offset of each (uint64; version 3: uint32) and their count (uint32). Flag 0x0010 (face
// normals) drops the normals. One material, named after the shape, covers every triangle.
//
// Every count is checked against what the file can hold before anything is allocated (zlib
// compresses at most 1032:1), every index against the vertex count. Throws std::runtime_error
// with the reason and the place, without the path.
MeshFile read_serialized_mesh(const std::filesystem::path& path, uint32_t shape_index);

}  // namespace wavetrace
