// A point sampled on a light as seen from a reference point: what LightSet::sample returns
// (shading/lights.h) and next-event estimation weighs.
#pragma once

#include "wavetrace/math/constants.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct LightSample {
    Vec3 wi;                 // unit direction from the reference point to the light
    float dist = kInfinity;  // to the sampled point (infinity for the background)
    Color radiance{0.0f};    // emitted towards the reference point (0 from a back face)
    float pdf = 0.0f;        // solid angle, selection included
    PrimRef prim;            // invalid for the background and point lights
    bool delta = false;      // a point light: pdf is the selection probability alone
    bool valid = false;
};

// The LightSample of a direction sampled from the environment map (EnvironmentLightPoint's wi,
// radiance and density, selection included): valid wherever the density is finite and positive,
// radiance or not, since the one-sample strategies continue the path along it.
inline LightSample environment_light_sample(Vec3 wi, Color radiance, float pdf) {
    LightSample ls;
    ls.wi = wi;
    ls.radiance = radiance;
    ls.pdf = pdf;
    ls.valid = pdf > 0.0f && pdf < kInfinity;
    return ls;
}

}  // namespace wavetrace
