#include "formats/affine.h"

#include <utility>

namespace wavetrace::affine {

M4 mul(const M4& a, const M4& b) {
    M4 r{};
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) r[i * 4 + j] += a[i * 4 + k] * b[k * 4 + j];
    return r;
}

bool invert(const M4& m, M4* out) {
    double a[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 8; ++j) a[i][j] = j < 4 ? m[i * 4 + j] : (j - 4 == i ? 1 : 0);
    for (int c = 0; c < 4; ++c) {
        int p = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::abs(a[r][c]) > std::abs(a[p][c])) p = r;
        if (!(std::abs(a[p][c]) > 1e-300)) return false;
        std::swap(a[c], a[p]);
        const double d = a[c][c];
        for (double& x : a[c]) x /= d;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            const double f = a[r][c];
            for (int j = 0; j < 8; ++j) a[r][j] -= f * a[c][j];
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) (*out)[i * 4 + j] = a[i][j + 4];
    return true;
}

V3 apply_point(const M4& m, V3 p) {
    return {m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3],
            m[4] * p[0] + m[5] * p[1] + m[6] * p[2] + m[7],
            m[8] * p[0] + m[9] * p[1] + m[10] * p[2] + m[11]};
}

V3 apply_vector(const M4& m, V3 v) {
    return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[4] * v[0] + m[5] * v[1] + m[6] * v[2],
            m[8] * v[0] + m[9] * v[1] + m[10] * v[2]};
}

M4 rotation(double degrees, V3 axis) {
    constexpr double kPi = 3.14159265358979323846;
    const V3 a = normalized(axis);
    const double s = std::sin(degrees * kPi / 180), c = std::cos(degrees * kPi / 180);
    return {a[0] * a[0] + (1 - a[0] * a[0]) * c, a[0] * a[1] * (1 - c) - a[2] * s,
            a[0] * a[2] * (1 - c) + a[1] * s, 0,
            a[0] * a[1] * (1 - c) + a[2] * s, a[1] * a[1] + (1 - a[1] * a[1]) * c,
            a[1] * a[2] * (1 - c) - a[0] * s, 0,
            a[0] * a[2] * (1 - c) - a[1] * s, a[1] * a[2] * (1 - c) + a[0] * s,
            a[2] * a[2] + (1 - a[2] * a[2]) * c, 0,
            0, 0, 0, 1};
}

bool rotation_axes(const M4& m, std::array<V3, 3>* axes, bool* rigid) {
    const V3 x = apply_vector(m, {1, 0, 0}), y = apply_vector(m, {0, 1, 0}),
             z = apply_vector(m, {0, 0, 1});
    const double det = dot(x, cross(y, z));
    const double scale = std::cbrt(std::abs(det));
    if (!(scale > 1e-12) || !std::isfinite(scale)) return false;
    const V3 ax = normalized(x);
    const double yx = dot(y, ax);
    const V3 ay = normalized({y[0] - yx * ax[0], y[1] - yx * ax[1], y[2] - yx * ax[2]});
    V3 az = cross(ax, ay);
    if (det < 0) az = {-az[0], -az[1], -az[2]};
    *axes = {ax, ay, az};
    *rigid = true;
    const V3 cols[3] = {x, y, z};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            if (std::abs(dot(cols[i], cols[j]) / (scale * scale) - (i == j ? 1 : 0)) > 1e-5)
                *rigid = false;
    return true;
}

nlohmann::json axes_matrix(const std::array<V3, 3>& a) {
    return nlohmann::json::array({nlohmann::json::array({a[0][0], a[1][0], a[2][0]}),
                                  nlohmann::json::array({a[0][1], a[1][1], a[2][1]}),
                                  nlohmann::json::array({a[0][2], a[1][2], a[2][2]})});
}

}  // namespace wavetrace::affine
