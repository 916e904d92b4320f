// What the rough dielectric coating of a plastic lets through, tabulated once per material
// (bsdfs/plastic.h says how it is used and computed).
#pragma once

#include <array>

namespace wavetrace {

struct CoatingTable {
    static constexpr int kSize = 64;
    // The share of light from a direction at cos theta = i / 63 (the first node at 1e-6) that
    // the coating refracts into the material, looked up linearly in between.
    std::array<float, kSize> transmittance{};
    // The share of light diffused inside the coating that is reflected back in.
    float internal_reflectance = 0.0f;

    float transmittance_at(float cos_theta) const;
};

}  // namespace wavetrace
