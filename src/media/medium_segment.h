// What the medium a path is in does to one straight segment, for both engines' flights and
// shadow rays: homogeneous media by Beer-Lambert (free_flight.h, and the grey flight's lane
// formula in medium_flight-inl.h), heterogeneous ones by their grid's exact optical depth
// (grid_track.h).
#pragma once

#include "media/free_flight.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

// The transmittance of a heterogeneous medium from o along unit direction dir for `length`.
// (Both grid functions stay out of line: inlined, their walk would crowd the homogeneous
// media's hot paths.)
[[gnu::noinline]] Color grid_transmittance(
    const Medium& medium, const VolumeGrid& grid, Point3 o, Vec3 dir, float length);

// Transmittance per channel of the part [t0, t1] of a ray (t1 infinite: nothing ends it) in
// medium m (not kNone).
inline Color segment_transmittance(
    const Scene& scene, MediumId m, const Ray& ray, float t0, float t1) {
    const Medium& medium = scene.media[m];
    const float len = length(ray.d);
    if (!medium.heterogeneous()) return medium_transmittance(medium.sigma_t, (t1 - t0) * len);
    return grid_transmittance(medium, scene.volume_grids[medium.density_grid], ray.at(t0),
                              ray.d / len, (t1 - t0) * len);
}

// The free flight through a heterogeneous medium from o along unit direction dir for `seg`
// (infinite: it hits nothing), with the optical depth `flight` still to travel: true when the
// path scatters first, at distance *s from o; else the depth the segment crosses is spent from
// `flight`. *weight multiplies the path's throughput: 1 for a grey grid (the sampling density
// is the transmittance's own), the channel mixture's weight in a chromatic one. (Homogeneous
// media: chromatic_flight, and the grey flight of medium_flight-inl.h.)
[[gnu::noinline]] bool grid_flight(const Medium& medium,
                                   const VolumeGrid& grid,
                                   Point3 o,
                                   Vec3 dir,
                                   float seg,
                                   float& flight,
                                   float* s,
                                   Color* weight);

}  // namespace wavetrace
