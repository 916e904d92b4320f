#pragma once

#include "kernels/wave.h"
#include "wavetrace/scene/intersector.h"

namespace wavetrace {

// Closest hit of rays[i] into hits[i].
template <Intersector Tracer>
void intersect(const Tracer& tracer, WaveQueues& q, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
        Hit hit = tracer.intersect(Ray{q.rays.origin[i], q.rays.dir[i], q.rays.tmin[i]});
        q.hits.t[i] = hit.t;
        q.hits.prim[i] = hit.prim;
        q.hits.u[i] = hit.u;
        q.hits.v[i] = hit.v;
    }
}

}  // namespace wavetrace
