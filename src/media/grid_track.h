// Optical depth along a ray through a grid medium (a VolumeGrid's extinction times a scale per
// channel, zero outside the grid's box, as Mitsuba 3's heterogeneous medium), computed exactly
// rather than estimated: between voxel centres the trilinear extinction along a line is a
// cubic in the distance, whose integral is closed-form, so a walk over those cells sums the
// depth, and a flight ends where it reaches the depth drawn for it (the inversion method, the
// "regular tracking" of Novák et al. 2018, "Monte Carlo methods for volumetric light transport
// simulation", §4.1, with analytic integration per cell). It needs no majorant and no random
// numbers beyond the one depth per segment that homogeneous media draw, and its transmittance
// carries no estimator noise (delta and ratio tracking, Mitsuba's, reach the same expectation
// with more variance).
#pragma once

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/volume_grid.h"

namespace wavetrace {

struct GridReach {
    bool reached = false;  // channel c's depth reached the target within the length
    float dist = 0.0f;     // reached: distance from the origin along the ray
    Color depth{0.0f};     // optical depth of every channel up to dist (else the whole length)
    Color sigma{0.0f};     // reached: the extinction of every channel there
};

// From world point o along unit direction dir for `length` (may be infinite): where channel
// c's optical depth first reaches `target` (infinite: never, giving the whole length's depth).
GridReach grid_reach(
    const VolumeGrid& grid, Color scale, Point3 o, Vec3 dir, float length, int c, float target);

}  // namespace wavetrace
