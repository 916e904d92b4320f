#pragma once

#include <cstdint>
#include <string>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

// A medium filling the inside of one or more closed boundary shapes (constant_medium in Ray
// Tracing: The Next Week, with an extinction per channel as Mitsuba 3's and pbrt-v4's
// homogeneous media): extinction coefficients sigma_t per world unit; scattering follows
// `phase` (an Isotropic material whose albedo is the single-scattering albedo
// sigma_s / sigma_t, a texture that may vary in space). A heterogeneous medium (Mitsuba 3's
// `heterogeneous` over a `gridvolume`) multiplies sigma_t by a grid's values inside the grid's
// box and is empty outside it.
// How crossing a medium boundary changes the medium a path is in.
enum class MediumBoundaries : uint8_t {
    // Boundaries nest: entering a shape puts the path in its interior medium, leaving it puts
    // the path back in the medium it was in before (a glass of water in fog).
    Nested,
    // Mitsuba 3's rule (and pbrt-v4's, for shapes without an outside medium): the medium after
    // a crossing is the crossed shape's own, its interior when entering and vacuum when
    // leaving, whatever the path was in before; overlapping shapes of one medium are not
    // merged, so leaving one inside the other reaches vacuum.
    Interface,
};

struct Medium {
    std::string name;
    Color sigma_t{0.0f};  // extinction per world unit, each channel >= 0
    MaterialId phase = kNone;
    VolumeGridId density_grid = kNone;  // into Scene::volume_grids; kNone: homogeneous

    bool heterogeneous() const { return density_grid != kNone; }

    // Whether the channels' extinctions differ: free flights then pick a channel to sample
    // (path_vertex.h) and carry a weight; grey media sample sigma_t exactly, with none. (A grid
    // of three channels makes a heterogeneous medium chromatic as well: medium_segment.h.)
    bool chromatic() const { return sigma_t.x != sigma_t.y || sigma_t.y != sigma_t.z; }
};

}  // namespace wavetrace
