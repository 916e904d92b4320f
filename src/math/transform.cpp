#include "wavetrace/math/transform.h"

#include <algorithm>
#include <cmath>

#include "wavetrace/math/constants.h"

namespace wavetrace {

Transform::Transform(const Mat4& m, const Mat4& inv) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            m_[i][j] = m[i][j];
            inv_[i][j] = inv[i][j];
        }
}

Transform Transform::translate(Vec3 t) {
    Mat4 m = {{1, 0, 0, t.x}, {0, 1, 0, t.y}, {0, 0, 1, t.z}, {0, 0, 0, 1}};
    Mat4 inv = {{1, 0, 0, -t.x}, {0, 1, 0, -t.y}, {0, 0, 1, -t.z}, {0, 0, 0, 1}};
    return Transform(m, inv);
}

Transform Transform::scale(Vec3 s) {
    Mat4 m = {{s.x, 0, 0, 0}, {0, s.y, 0, 0}, {0, 0, s.z, 0}, {0, 0, 0, 1}};
    Mat4 inv = {{1 / s.x, 0, 0, 0}, {0, 1 / s.y, 0, 0}, {0, 0, 1 / s.z, 0}, {0, 0, 0, 1}};
    return Transform(m, inv);
}

bool Transform::affine(const double rows[3][4], Transform* out) {
    const double (*a)[4] = rows;
    // The inverse of L by its adjugate over its determinant; the translation's by -L^-1 t.
    const double c00 = a[1][1] * a[2][2] - a[1][2] * a[2][1];
    const double c01 = a[1][2] * a[2][0] - a[1][0] * a[2][2];
    const double c02 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    const double det = a[0][0] * c00 + a[0][1] * c01 + a[0][2] * c02;
    double scale = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) scale = std::max(scale, std::abs(a[i][j]));
    if (!std::isfinite(det) || !(std::abs(det) > 1e-21 * scale * scale * scale)) return false;
    double inv[3][3] = {
        {c00, a[0][2] * a[2][1] - a[0][1] * a[2][2], a[0][1] * a[1][2] - a[0][2] * a[1][1]},
        {c01, a[0][0] * a[2][2] - a[0][2] * a[2][0], a[0][2] * a[1][0] - a[0][0] * a[1][2]},
        {c02, a[0][1] * a[2][0] - a[0][0] * a[2][1], a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
    Mat4 m = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 1}};
    Mat4 mi = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 1}};
    for (int i = 0; i < 3; ++i) {
        double t = 0.0;
        for (int j = 0; j < 3; ++j) {
            inv[i][j] /= det;
            t -= inv[i][j] * a[j][3];
        }
        for (int j = 0; j < 4; ++j) m[i][j] = static_cast<float>(a[i][j]);
        for (int j = 0; j < 3; ++j) mi[i][j] = static_cast<float>(inv[i][j]);
        mi[i][3] = static_cast<float>(t);
    }
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j)
            if (!std::isfinite(m[i][j]) || !std::isfinite(mi[i][j])) return false;
    *out = Transform(m, mi);
    return true;
}

// Rodrigues' rotation formula; the inverse of a rotation is its transpose.
Transform Transform::rotate(Vec3 axis, float degrees) {
    Vec3 a = normalize(axis);
    float s = std::sin(radians(degrees)), c = std::cos(radians(degrees));
    Mat4 m = {{a.x * a.x + (1 - a.x * a.x) * c, a.x * a.y * (1 - c) - a.z * s,
               a.x * a.z * (1 - c) + a.y * s, 0},
              {a.x * a.y * (1 - c) + a.z * s, a.y * a.y + (1 - a.y * a.y) * c,
               a.y * a.z * (1 - c) - a.x * s, 0},
              {a.x * a.z * (1 - c) - a.y * s, a.y * a.z * (1 - c) + a.x * s,
               a.z * a.z + (1 - a.z * a.z) * c, 0},
              {0, 0, 0, 1}};
    Mat4 inv;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) inv[i][j] = m[j][i];
    return Transform(m, inv);
}

Transform Transform::operator*(const Transform& first) const {
    Mat4 m, inv;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            m[i][j] = 0;
            inv[i][j] = 0;
            for (int k = 0; k < 4; ++k) {
                m[i][j] += m_[i][k] * first.m_[k][j];
                inv[i][j] += first.inv_[i][k] * inv_[k][j];
            }
        }
    return Transform(m, inv);
}

Point3 Transform::point(Point3 p) const {
    return {m_[0][0] * p.x + m_[0][1] * p.y + m_[0][2] * p.z + m_[0][3],
            m_[1][0] * p.x + m_[1][1] * p.y + m_[1][2] * p.z + m_[1][3],
            m_[2][0] * p.x + m_[2][1] * p.y + m_[2][2] * p.z + m_[2][3]};
}

Vec3 Transform::vector(Vec3 v) const {
    return {m_[0][0] * v.x + m_[0][1] * v.y + m_[0][2] * v.z,
            m_[1][0] * v.x + m_[1][1] * v.y + m_[1][2] * v.z,
            m_[2][0] * v.x + m_[2][1] * v.y + m_[2][2] * v.z};
}

// Normals transform by the inverse transpose of the linear part.
Normal3 Transform::normal(Normal3 n) const {
    return {inv_[0][0] * n.x + inv_[1][0] * n.y + inv_[2][0] * n.z,
            inv_[0][1] * n.x + inv_[1][1] * n.y + inv_[2][1] * n.z,
            inv_[0][2] * n.x + inv_[1][2] * n.y + inv_[2][2] * n.z};
}

bool Transform::is_identity() const {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (m_[i][j] != (i == j ? 1.0f : 0.0f)) return false;
    return true;
}

bool Transform::flips_handedness() const {
    Vec3 c0{m_[0][0], m_[1][0], m_[2][0]}, c1{m_[0][1], m_[1][1], m_[2][1]},
        c2{m_[0][2], m_[1][2], m_[2][2]};
    return dot(cross(c0, c1), c2) < 0.0f;
}

// M^T M = s^2 I exactly when M is a rotation (or reflection) times a uniform scale s.
bool Transform::preserves_shape(float* uniform_scale) const {
    Vec3 c[3] = {{m_[0][0], m_[1][0], m_[2][0]},
                 {m_[0][1], m_[1][1], m_[2][1]},
                 {m_[0][2], m_[1][2], m_[2][2]}};
    float s2 = dot(c[0], c[0]);
    constexpr float tol = 1e-5f;
    for (int i = 0; i < 3; ++i) {
        if (std::fabs(dot(c[i], c[i]) - s2) > tol * s2) return false;
        for (int j = i + 1; j < 3; ++j)
            if (std::fabs(dot(c[i], c[j])) > tol * s2) return false;
    }
    if (uniform_scale) *uniform_scale = std::sqrt(s2);
    return true;
}

bool Transform::is_well_conditioned(float max_scale) const {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!std::isfinite(m_[i][j]) || !std::isfinite(inv_[i][j])) return false;
    // The largest entry of the linear part bounds how far it stretches; of its inverse, how
    // far it shrinks.
    float stretch = 0, shrink = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            stretch = std::max(stretch, std::fabs(m_[i][j]));
            shrink = std::max(shrink, std::fabs(inv_[i][j]));
        }
    return stretch <= max_scale && shrink <= max_scale;
}

}  // namespace wavetrace
