// A 3-D grid of values over a box: the extinction of a heterogeneous medium, or a texture read
// at points in space (a medium's albedo). Mitsuba 3's `gridvolume`: the grid spans the unit
// cube of its own frame and `to_local` maps world points there; voxel (i, j, k)'s value sits
// at its centre ((i + 0.5) / nx, (j + 0.5) / ny, (k + 0.5) / nz) and values between centres
// are interpolated trilinearly (`filter_type` trilinear), or each voxel's value fills its cell
// (nearest); indices beyond the grid are clamped to its edge, repeat it, or mirror it
// (`wrap_mode`), or read black (pbrt-v4's grid media).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "wavetrace/math/transform.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

struct VolumeGrid {
    std::string path;        // where it was read from, for messages
    int res[3] = {0, 0, 0};  // voxels along x, y, z
    int channels = 1;        // 1 (grey) or 3 (RGB)
    // res[0] * res[1] * res[2] * channels values, >= 0: x varies fastest, then y, then z, the
    // channels of one voxel together.
    std::vector<float> values;
    Transform to_local;  // world to the grid's unit cube
    bool nearest = false;  // each voxel's value over its whole cell, not interpolated
    TextureWrap wrap = TextureWrap::Clamp;  // how indices beyond the grid are brought in

    // The value of voxel (i, j, k), each index brought into the grid by `wrap`; a grey grid's
    // one channel in all three.
    Color voxel(int i, int j, int k) const;
    // The filtered value at a point of the grid's frame (the unit cube and beyond).
    Color lookup_local(Point3 q) const;
    Color lookup(Point3 world) const { return lookup_local(to_local.point(world)); }
};

}  // namespace wavetrace
