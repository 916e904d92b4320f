// The lights that next-event estimation samples in SIMD lanes (src/lights/light_sample-inl.h,
// sphere_light-inl.h), as columns that LightSet fills (shading/lights.h) and the lane kernels
// gather from.
#pragma once

#include <vector>

namespace wavetrace {

// The quad and triangle lights of constant radiance (the case next-event estimation at lane
// vertices samples in SIMD lanes, src/lights/light_sample-inl.h) as columns, entry k for
// planar emitter k (planar_emitter_index()): corner q, edges u and v (a triangle's p0, p1 - p0
// and p2 - p0), the front normal n = normalize(cross(u, v)), the
// area, the radiance, two_sided and triangle (1 or 0).
struct PlanarEmitterColumns {
    std::vector<float> q[3], u[3], v[3], n[3], radiance[3], area, two_sided, triangle;
};

// The sphere lights of constant radiance (sampled in SIMD lanes from outside the sphere,
// src/lights/sphere_light-inl.h) as columns, entry k for sphere emitter k
// (sphere_emitter_index()): centre, radius, radiance, and two_sided (1 or 0).
struct SphereEmitterColumns {
    std::vector<float> centre[3], radius, radiance[3], two_sided;
};

// The point and directional lights (sampled in SIMD lanes, src/lights/light_sample-inl.h) as
// columns, entry k for delta light k (delta_light_index()): a point light's position and
// radiant intensity, or a directional light's direction towards it (-Light::direction) and
// irradiance, and directional (1 or 0). Spots and projectors are not among them.
struct DeltaLightColumns {
    std::vector<float> at[3], intensity[3], directional;
};

}  // namespace wavetrace
