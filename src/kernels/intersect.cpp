#include "kernels/kernels.h"

namespace wavetrace {

void intersect(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
        Hit hit = in.bvh.intersect(Ray{q.rays.origin[i], q.rays.dir[i], q.rays.tmin[i]});
        q.hits.t[i] = hit.t;
        q.hits.prim[i] = hit.prim;
        q.hits.u[i] = hit.u;
        q.hits.v[i] = hit.v;
    }
}

}  // namespace wavetrace
