#include "media/medium_segment.h"

#include <cmath>

#include "media/free_flight.h"
#include "media/grid_track.h"

namespace wavetrace {
namespace {

Color exp_minus(Color depth) {
    return {std::exp(-depth.x), std::exp(-depth.y), std::exp(-depth.z)};
}

}  // namespace

Color grid_transmittance(
    const Medium& medium, const VolumeGrid& grid, Point3 o, Vec3 dir, float length) {
    return exp_minus(grid_reach(grid, medium.sigma_t, o, dir, length, 0, kInfinity).depth);
}

bool grid_flight(const Medium& medium,
                 const VolumeGrid& grid,
                 Point3 o,
                 Vec3 dir,
                 float seg,
                 float& flight,
                 float* s,
                 Color* weight) {
    // As chromatic_flight, with the grid's depths and extinctions for sigma_t t and sigma_t.
    const bool chromatic = medium.chromatic() || grid.channels == 3;
    const int c = chromatic ? draw_flight_channel(flight) : 0;
    const GridReach r = grid_reach(grid, medium.sigma_t, o, dir, seg, c, flight);
    *weight = Color(1.0f);
    if (r.reached) {
        *s = r.dist;
        if (chromatic) *weight = channel_mixture_weight(r.sigma * exp_minus(r.depth));
        return true;
    }
    if (chromatic) *weight = channel_mixture_weight(exp_minus(r.depth));
    flight -= r.depth[c];
    return false;
}

}  // namespace wavetrace
