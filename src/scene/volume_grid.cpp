#include "wavetrace/scene/volume_grid.h"

#include <algorithm>
#include <cmath>

namespace wavetrace {

Color VolumeGrid::voxel(int i, int j, int k) const {
    i = std::clamp(i, 0, res[0] - 1);
    j = std::clamp(j, 0, res[1] - 1);
    k = std::clamp(k, 0, res[2] - 1);
    const size_t at = ((static_cast<size_t>(k) * res[1] + j) * res[0] + i) * channels;
    return channels == 1 ? Color(values[at]) : Color(values[at], values[at + 1], values[at + 2]);
}

Color VolumeGrid::lookup_local(Point3 q) const {
    // Index space: voxel centres at integers.
    const float u[3] = {q.x * res[0] - 0.5f, q.y * res[1] - 0.5f, q.z * res[2] - 0.5f};
    int base[3];
    float f[3];
    for (int a = 0; a < 3; ++a) {
        // Far outside (or NaN), clamp before the conversion to int can overflow.
        const float x = std::fmin(std::fmax(u[a], -1.0f), float(res[a]));
        const float fl = std::floor(x);
        base[a] = static_cast<int>(fl);
        f[a] = x - fl;
    }
    Color c{0.0f};
    for (int dz = 0; dz < 2; ++dz)
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                const float w = (dx ? f[0] : 1.0f - f[0]) * (dy ? f[1] : 1.0f - f[1]) *
                                (dz ? f[2] : 1.0f - f[2]);
                c += w * voxel(base[0] + dx, base[1] + dy, base[2] + dz);
            }
    return c;
}

}  // namespace wavetrace
