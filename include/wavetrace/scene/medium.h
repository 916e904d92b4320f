#pragma once

#include <string>

#include "wavetrace/scene/ids.h"

namespace wavetrace {

// Homogeneous medium filling the inside of one or more closed convex boundary shapes
// (constant_medium in Ray Tracing: The Next Week). Extinction coefficient sigma_t = density, the
// same in every channel; scattering follows `phase` (an Isotropic material whose albedo is the
// single-scattering albedo sigma_s / sigma_t).
struct Medium {
    std::string name;
    float density = 0.0f;  // per world unit
    MaterialId phase = kNone;
};

}  // namespace wavetrace
