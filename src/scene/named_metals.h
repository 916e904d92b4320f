// Conductors by name: the complex index of refraction eta + i k in linear sRGB of the metals
// (and some crystals) Mitsuba names, derived from measured spectra by tools/named-metals.py
// (its docstring gives the method: Mitsuba's for its RGB variants, so that Mitsuba scenes naming
// a metal match their RGB references).
#pragma once

#include <span>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

struct NamedMetal {
    const char* name;  // as Mitsuba spells it: "Au", "Ag", "Cu", "Al", "Cr", "Ni_palik", ...
    Color eta, k;
};

std::span<const NamedMetal> named_metals();

}  // namespace wavetrace
