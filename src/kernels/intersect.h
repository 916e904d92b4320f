#pragma once

#include "kernels/wave.h"
#include "wavetrace/scene/intersector.h"

namespace wavetrace {

// Closest hit of rays[i] into hits[i].
template <Intersector Tracer>
void intersect(
    const Tracer& tracer, const RayQueue& rays, size_t begin, size_t end, HitQueue& hits) {
    for (size_t i = begin; i < end; ++i) {
        Hit hit = tracer.intersect(ray_at(rays, i));
        hits.t[i] = hit.t;
        hits.prim[i] = hit.prim;
        hits.u[i] = hit.u;
        hits.v[i] = hit.v;
    }
}

}  // namespace wavetrace
