#pragma once

#include <limits>

namespace wavetrace {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Bound on the relative rounding error of n floating-point operations (pbrt-v4, eq. 6.29):
// gamma(n) = n u / (1 - n u), with u the unit roundoff.
constexpr float gamma(int n) {
    constexpr float u = std::numeric_limits<float>::epsilon() * 0.5f;
    return (n * u) / (1 - n * u);
}

constexpr float radians(float degrees) {
    return degrees * (kPi / 180.0f);
}

}  // namespace wavetrace
