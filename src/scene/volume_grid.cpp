#include "wavetrace/scene/volume_grid.h"

#include <cmath>

namespace wavetrace {

Color VolumeGrid::voxel(int i, int j, int k) const {
    i = wrap_index(i, res[0], wrap);
    j = wrap_index(j, res[1], wrap);
    k = wrap_index(k, res[2], wrap);
    if (i < 0 || j < 0 || k < 0) return Color(0.0f);  // black beyond the grid
    const size_t at = ((static_cast<size_t>(k) * res[1] + j) * res[0] + i) * channels;
    return channels == 1 ? Color(values[at]) : Color(values[at], values[at + 1], values[at + 2]);
}

Color VolumeGrid::lookup_local(Point3 q) const {
    int base[3];
    float f[3];
    for (int a = 0; a < 3; ++a) {
        // Repeat and mirror first bring the point into one period; then clamp far outside (or
        // NaN) before the conversion to int can overflow.
        float x = q[a];
        if (wrap == TextureWrap::Repeat) x -= std::floor(x);
        if (wrap == TextureWrap::Mirror)
            x = 1.0f - std::fabs(1.0f - (x - 2.0f * std::floor(0.5f * x)));
        // Index space: voxel centres at integers (trilinear), cells [i, i + 1) (nearest).
        x = x * res[a] - (nearest ? 0.0f : 0.5f);
        x = std::fmin(std::fmax(x, -1.0f), float(res[a]));
        const float fl = std::floor(x);
        base[a] = static_cast<int>(fl);
        f[a] = x - fl;
    }
    if (nearest) return voxel(base[0], base[1], base[2]);
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
