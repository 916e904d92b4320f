#pragma once

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Clarberg's equal-area octahedral mapping between the unit square and the unit sphere
// ("Fast Equal-Area Mapping of the (Hemi)Sphere using SIMD", JGT 13(3), 2008), in the layout
// pbrt-v4 stores its environment images in: the square's centre (0.5, 0.5) is +z, its four
// corners -z, the inner diamond |2u - 1| + |2v - 1| <= 1 the hemisphere z >= 0; (1, 0.5) is
// +x and (0.5, 1) is +y. Every region of the square maps to a region of the sphere 4 pi times
// its area, so a texel of an N x N image subtends 4 pi / N^2 steradians.

// The one-lane instances of math/equal_area-inl.h, which the wavefront runs in SIMD lanes.

// (u, v) in [0, 1]^2 to a unit direction.
Vec3 equal_area_square_to_sphere(float u, float v);
// A unit direction to (u, v) in [0, 1]^2; the inverse of the above.
Vec2 equal_area_sphere_to_square(Vec3 d);

}  // namespace wavetrace
