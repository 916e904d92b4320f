#include "math/equal_area.h"

#include <algorithm>
#include <cmath>

#include "wavetrace/math/constants.h"

namespace wavetrace {

// In the square's coordinates a = 2u - 1, b = 2v - 1, the L1 distance s = |a| + |b| from the
// centre gives the polar distance: r = s inside the diamond s <= 1 (z >= 0), r = 2 - s outside
// it (the four corner triangles folded over to z < 0), with |z| = 1 - r^2 so that areas are
// kept; the position along the diamond's edge gives the azimuth within the quadrant,
// phi = pi/4 ((|b| - |a|) / r + 1), and the signs of a and b the quadrant.
Vec3 equal_area_square_to_sphere(float u, float v) {
    const float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;
    const float signed_distance = 1.0f - (std::fabs(a) + std::fabs(b));
    const float r = 1.0f - std::fabs(signed_distance);
    const float phi = (r == 0.0f ? 1.0f : (std::fabs(b) - std::fabs(a)) / r + 1.0f) * (kPi / 4);
    const float z = std::copysign(1.0f - r * r, signed_distance);
    const float planar = r * std::sqrt(std::max(0.0f, 2.0f - r * r));
    return {std::copysign(std::cos(phi), a) * planar, std::copysign(std::sin(phi), b) * planar, z};
}

Vec2 equal_area_sphere_to_square(Vec3 d) {
    const float x = std::fabs(d.x), y = std::fabs(d.y), z = std::fabs(d.z);
    // r = sqrt(1 - |z|), written so that it keeps its precision near the poles.
    const float r = std::sqrt((x * x + y * y) / (1.0f + z));
    const float t = std::atan2(y, x) * (2.0f / kPi);  // the azimuth in the quadrant, 0 .. 1
    float b = r * t, a = r - b;                       // on the diamond |a| + |b| = r
    if (d.z < 0.0f) {                                 // folded out to |a| + |b| = 2 - r
        std::swap(a, b);
        a = 1.0f - a;
        b = 1.0f - b;
    }
    a = std::copysign(a, d.x);
    b = std::copysign(b, d.y);
    return {std::clamp(0.5f * (a + 1.0f), 0.0f, 1.0f), std::clamp(0.5f * (b + 1.0f), 0.0f, 1.0f)};
}

}  // namespace wavetrace
