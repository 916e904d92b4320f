// Which vertices the lane formulas take (shading/*-inl.h templates over SIMD lanes): the
// routing both engines follow. The megakernel runs those formulas with one lane inside
// continue_path and next_event; the wavefront's shade and light_sample kernels gather the same
// vertices into lane blocks. One rule for both, so that a vertex takes the same formula in each.
#pragma once

#include <cstdint>

#include "bsdfs/lane_lobe.h"
#include "shading/lights.h"
#include "shading/path_vertex.h"
#include "wavetrace/shading/estimator.h"

namespace wavetrace {

// Whether the continuation at v is a lane step (shading/surface_step-inl.h): a lane vertex
// whose direction the strategy samples from the BSDF or phase function. The wavefront runs
// these vertices' steps in SIMD lanes, continue_path the same formula in one lane.
bool takes_lane_step(const Estimator& config, const Vertex& v, const LightSet& lights);
// A surface of such a BSDF without a mapped normal's shadowing (bump_alpha2 0, Vertex), or a
// medium's isotropic phase function (ng = 0): the vertices the lane formulas of next-event
// estimation towards quad, triangle, sphere, point, directional and environment lights and of
// the continuation take.
inline bool is_lane_vertex(Normal3 ng, const BsdfParams& b, float bump_alpha2) {
    if (ng.x == 0 && ng.y == 0 && ng.z == 0) return b.kind == MaterialKind::Isotropic;
    return bump_alpha2 == 0.0f && is_lane_bsdf(b);
}
inline bool is_lane_vertex(const Vertex& v) {
    return is_lane_vertex(v.ng, v.bsdf, v.bump_alpha2);
}

// The light next_event samples at v in SIMD lanes (lights/light_sample-inl.h), as its index
// among the LightSet's planar emitters, or -1: at a lane vertex (is_lane_vertex) that
// samples_lights(), a chosen quad or triangle of constant radiance.
inline int32_t planar_light_sample_at(bool lane_vertex,
                                      const LightSet& lights,
                                      LightChoice choice) {
    return lane_vertex ? lights.planar_emitter_index(choice) : -1;
}
inline int32_t planar_light_sample_at(const Vertex& v, const LightSet& lights, LightChoice choice) {
    return planar_light_sample_at(is_lane_vertex(v), lights, choice);
}
// The same for a chosen sphere of constant radiance with the vertex at p outside it
// (lights/sphere_light-inl.h), as its index among the LightSet's sphere emitters, or -1.
int32_t sphere_light_sample_at(Point3 p,
                               bool lane_vertex,
                               const LightSet& lights,
                               LightChoice choice);
inline int32_t sphere_light_sample_at(const Vertex& v, const LightSet& lights, LightChoice choice) {
    return sphere_light_sample_at(v.p, is_lane_vertex(v), lights, choice);
}
// The same for a chosen point or directional light (DeltaLightPoint), as its index among the
// LightSet's delta light columns, or -1.
inline int32_t delta_light_sample_at(bool lane_vertex, const LightSet& lights, LightChoice choice) {
    return lane_vertex ? lights.delta_light_index(choice) : -1;
}
// Whether the chosen light is an environment map, sampled at a lane vertex by
// EnvironmentLightPoint (lights/environment_light-inl.h).
inline bool environment_light_sample_at(bool lane_vertex,
                                        const LightSet& lights,
                                        LightChoice choice) {
    return lane_vertex && lights.is_environment(choice);
}
inline bool environment_light_sample_at(const Vertex& v,
                                        const LightSet& lights,
                                        LightChoice choice) {
    return environment_light_sample_at(is_lane_vertex(v), lights, choice);
}

}  // namespace wavetrace
