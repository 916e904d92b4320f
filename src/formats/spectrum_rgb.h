// Spectra to linear sRGB, as Mitsuba 3's RGB variants convert the spectra of a scene file.
#pragma once

#include <utility>
#include <vector>

#include "wavetrace/math/vec3.h"

namespace wavetrace {

// A spectrum given at wavelengths in nm (increasing), linearly interpolated between them and
// zero outside, integrated against the CIE 1931 2-degree colour matching functions (5 nm
// table, linearly interpolated) at 1000 evenly spaced wavelengths over 360-830 nm, divided by
// the integral of y-bar and taken from XYZ to linear sRGB (IEC 61966-2-1); negative channels
// become 0 and, for a reflectance (`bounded`), channels above 1 become 1. A flat spectrum of
// value 1 gives about (1.0, 1.0, 1.0) only approximately: sRGB's white is D65, not flat.
// tools/spectra.py is the same computation, used to write named_metals.cpp.
Color spectrum_to_rgb(const std::vector<std::pair<double, double>>& points, bool bounded);

// Planck's law for a black body at `kelvin`, in W m^-2 sr^-1 nm^-1 at wavelength `nm`.
double planck(double nm, double kelvin);

// The colour Mitsuba 3's RGB variants give the CIE D65 illuminant of unit luminance: the
// default radiance of its emitters.
inline constexpr Color kD65Rgb{1.001084089f, 0.999707818f, 0.999703050f};

}  // namespace wavetrace
