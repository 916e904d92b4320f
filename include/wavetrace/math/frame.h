#pragma once

#include <cmath>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Orthonormal frame around a unit normal n, built without branches on the normal's
// direction: Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017.
struct Frame {
    Vec3 s, t, n;

    // The one-lane instance of OrthonormalBasis (src/shading/lanes-inl.h), which the
    // wavefront's kernels run over SIMD lanes.
    static Frame from_normal(Vec3 n);
    constexpr Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    constexpr Vec3 to_world(Vec3 v) const { return v.x * s + v.y * t + v.z * n; }
    // True when s, t, n are finite, of unit length and perpendicular to within `tolerance`
    // (a rotation, possibly mirrored).
    bool is_orthonormal(float tolerance) const;
};

}  // namespace wavetrace
