#pragma once

#include "wavetrace/math/constants.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// A ray o + t d, valid for t in [tmin, tmax]. The direction need not be unit length;
// t is measured in units of |d|.
struct Ray {
    Point3 o;
    Vec3 d;
    float tmin = 0.0f;
    float tmax = kInfinity;

    constexpr Point3 at(float t) const { return o + t * d; }
};

// How far a new ray starts from the surface point p it leaves: relative to p's magnitude
// (about 170 float ulps), so that it clears the rounding error of p itself at any scale:
// 2e-5 (1 + max |p_i|). The one-lane instance of OriginOffset (src/shading/lanes-inl.h).
float origin_offset(Point3 p);

}  // namespace wavetrace
