// Mitsuba's binary volume grids (`.vol`, the file of its `gridvolume`), read by our own code:
// the format is small and documented in Mitsuba 3's plugin reference.
#pragma once

#include <filesystem>

#include "wavetrace/math/aabb.h"
#include "wavetrace/scene/volume_grid.h"

namespace wavetrace {

// Reads the file's grid: the bytes 'V' 'O' 'L' 3, then little-endian int32 encoding (1: float32,
// the one Mitsuba 3 writes and reads), x, y and z resolution, channels (1 or 3 here), six
// float32 of a bounding box (the box the grid spans in its frame, read into *bounds where
// given; Mitsuba's use_grid_bbox, false by default, uses it), and the values, x fastest, a voxel's
// channels together. Every value must be finite and >= 0 (an extinction or an albedo). The file
// must hold exactly the values its header claims, checked before anything is allocated. Sets path,
// res, channels and values; to_local stays the identity. Throws std::runtime_error with the reason
// and the place (the byte offset or the voxel), without the path.
VolumeGrid read_volume_file(const std::filesystem::path& path, Aabb* bounds = nullptr);

}  // namespace wavetrace
