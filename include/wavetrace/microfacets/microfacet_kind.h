// The microfacet normal distributions of rough materials (src/microfacets/microfacet.h).
#pragma once

#include <cstdint>

namespace wavetrace {

enum class Microfacet : uint8_t {
    Ggx,       // Trowbridge-Reitz (Walter et al. 2007)
    Beckmann,  // Beckmann-Spizzichino
};

}  // namespace wavetrace
