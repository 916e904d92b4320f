// Triangle meshes as binary PLY files (the format of Greg Turk's "The PLY Polygon File
// Format"), readable by every mesh tool and by our own mesh reader.
#pragma once

#include <cstdint>
#include <vector>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// A binary little-endian PLY: vertices x y z, with nx ny nz if `normals` is not empty and u v
// if `uvs` is not empty (one per position), as floats; faces as lists of three int indices.
std::vector<unsigned char> encode_ply(const std::vector<Point3>& positions,
                                      const std::vector<Normal3>& normals,
                                      const std::vector<Vec2>& uvs,
                                      const std::vector<uint32_t>& indices);

}  // namespace wavetrace
