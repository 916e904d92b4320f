#pragma once

#include "wavetrace/math/constants.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Axis-aligned bounding box; the default box is empty (lo = +inf, hi = -inf) so that
// growing it by anything gives that thing's bounds.
struct Aabb {
    Vec3 lo{kInfinity};
    Vec3 hi{-kInfinity};

    constexpr void grow(Vec3 p) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    constexpr void grow(const Aabb& b) {
        lo = min(lo, b.lo);
        hi = max(hi, b.hi);
    }
    constexpr bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    constexpr Vec3 extent() const { return hi - lo; }
    constexpr Vec3 center() const { return 0.5f * (lo + hi); }
    constexpr float half_area() const {
        if (empty()) return 0.0f;
        Vec3 e = extent();
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
    constexpr bool contains(const Aabb& b) const {
        return b.empty() || (lo.x <= b.lo.x && lo.y <= b.lo.y && lo.z <= b.lo.z && hi.x >= b.hi.x &&
                             hi.y >= b.hi.y && hi.z >= b.hi.z);
    }
};

constexpr Aabb merge(Aabb a, const Aabb& b) {
    a.grow(b);
    return a;
}

}  // namespace wavetrace
