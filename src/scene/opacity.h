// Alpha masks: a material's opacity texture cuts its surfaces away where it is below 1, for
// every ray (camera, continuation and shadow rays alike), in both intersectors: our BVH's
// closest-hit, any-hit and packet traversals and Embree's filter functions call cut_away on each
// candidate hit of a masked primitive, and a cut-away hit is as if the surface were not there.
//
// Opacity a at the hit is the texture's luminance (Rec. 709 weights, as Mitsuba's `mask` reads
// a colour texture), clamped to [0, 1]. Where 0 < a < 1 the hit is kept with probability a,
// decided by a hash of the ray (origin, direction) and the primitive (pbrt-v4's stochastic
// alpha test): the same ray meets the same surface in both engines and both intersectors, so
// that images stay deterministic, and the expected image is that of a surface of coverage a.
#pragma once

#include "wavetrace/math/ray.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct Scene;

// Whether any material of the scene has an opacity texture.
bool has_alpha_masks(const Scene& scene);

// Whether the hit of `ray` on prim at distance t with parameters (u, v) is cut away.
bool cut_away(const Scene& scene, PrimRef prim, float t, float u, float v, const Ray& ray);

}  // namespace wavetrace
