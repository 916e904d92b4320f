// Double-precision affine maps of scene files (Mitsuba's <transform>, pbrt's CTM): composed,
// inverted and applied in double before the JSON loader takes them as float steps.
#pragma once

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

namespace wavetrace::affine {

using V3 = std::array<double, 3>;
using M4 = std::array<double, 16>;  // row-major; points are columns: M * p

inline V3 sub(V3 a, V3 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V3 add(V3 a, V3 b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline double dot(V3 a, V3 b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(V3 a, V3 b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 normalized(V3 a) {
    const double n = norm(a);
    return {a[0] / n, a[1] / n, a[2] / n};
}
inline nlohmann::json to_json(V3 v) { return nlohmann::json::array({v[0], v[1], v[2]}); }

inline M4 identity() { return {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; }
M4 mul(const M4& a, const M4& b);
// Gauss-Jordan with partial pivoting; false if singular.
bool invert(const M4& m, M4* out);
V3 apply_point(const M4& m, V3 p);
V3 apply_vector(const M4& m, V3 v);
// Rotation by `degrees` counter-clockwise about `axis` (non-zero), Rodrigues' formula.
M4 rotation(double degrees, V3 axis);

// The rotation in m's linear part: the images of the x, y and z axes made orthonormal
// (Gram-Schmidt from x, keeping m's handedness). False when the linear part is singular;
// *rigid tells whether it already was a rotation times a uniform scale (within 1e-5).
bool rotation_axes(const M4& m, std::array<V3, 3>* axes, bool* rigid);
// Axes as the columns of a 3 x 3 matrix, written as its rows (our JSON's `to_world`).
nlohmann::json axes_matrix(const std::array<V3, 3>& axes);

}  // namespace wavetrace::affine
