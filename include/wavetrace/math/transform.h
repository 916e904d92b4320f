#pragma once

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Affine transform as a row-major 4x4 matrix with its inverse kept alongside, so that
// normals transform by the inverse transpose without a second inversion.
class Transform {
  public:
    constexpr Transform() = default;

    static Transform translate(Vec3 t);
    static Transform scale(Vec3 s);  // every component must be non-zero
    // Rotation by `degrees` about `axis` (any non-zero vector), right-handed.
    static Transform rotate(Vec3 axis, float degrees);
    // The affine map p -> L p + t of a row-major 3x4 matrix [L | t], its inverse computed in
    // double precision; false when L is singular (|det L| below 1e-21 of its scale cubed) or
    // the result is not finite.
    static bool affine(const double rows[3][4], Transform* out);

    // this applied after `first`: (a * b)(p) = a(b(p)).
    Transform operator*(const Transform& first) const;

    Point3 point(Point3 p) const;
    Vec3 vector(Vec3 v) const;
    Normal3 normal(Normal3 n) const;  // not renormalized

    bool is_identity() const;
    // True when the matrix and its inverse hold only finite numbers and the linear part's
    // scale stays within [1/max_scale, max_scale]: a composition of valid steps can still
    // overflow (six scales by 1e7) or vanish.
    bool is_well_conditioned(float max_scale) const;
    // True when the transform mirrors (its linear part has a negative determinant): shapes
    // then need their winding flipped to keep their outside outside.
    bool flips_handedness() const;
    // True when the linear part is a rotation times a uniform scale, which maps spheres to spheres.
    bool preserves_shape(float* uniform_scale) const;
    Transform inverse() const { return Transform(inv_, m_); }

  private:
    using Mat4 = float[4][4];
    Transform(const Mat4& m, const Mat4& inv);

    float m_[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
    float inv_[4][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
};

}  // namespace wavetrace
