#pragma once

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// A point light: radiant intensity `intensity` (W sr^-1 per channel) from one point in every
// direction, so that a surface at distance d facing it receives intensity / d^2. A Dirac delta
// in position: no ray can hit it, so only next-event estimation (strategies nee and mis)
// reaches it, as in pbrt-v4 and Mitsuba 3 (their `point` lights).
struct PointLight {
    Point3 position;
    Color intensity{0.0f};
};

}  // namespace wavetrace
