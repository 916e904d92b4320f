// The current bounce's rays, one per live path, entry for entry with the path queue; and their
// closest hits. Rays start at t = 0 (camera rays and continuations alike), so no tmin is kept.
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

#define WAVETRACE_RAY_FIELDS(F)     \
    F(Point3, origin, "ray origin") \
    F(Vec3, dir, "ray direction (not necessarily unit)")

WAVETRACE_SOA(RayQueue, WAVETRACE_RAY_FIELDS);

inline Ray ray_at(const RayQueue& q, size_t i) {
    return Ray{q.origin[i], q.dir[i]};
}
inline void set_ray(RayQueue& q, size_t i, const Ray& r) {
    q.origin[i] = r.o;
    q.dir[i] = r.d;
}

#define WAVETRACE_HIT_FIELDS(F)                              \
    F(float, t, "hit distance in units of |dir|; inf: miss") \
    F(PrimRef, prim, "primitive hit (invalid: miss)")        \
    F(float, u, "surface parameter")                         \
    F(float, v, "surface parameter")

WAVETRACE_SOA(HitQueue, WAVETRACE_HIT_FIELDS);

inline Hit hit_at(const HitQueue& q, size_t i) {
    return Hit{q.t[i], q.prim[i], q.u[i], q.v[i]};
}
inline void set_hit(HitQueue& q, size_t i, const Hit& h) {
    q.t[i] = h.t;
    q.prim[i] = h.prim;
    q.u[i] = h.u;
    q.v[i] = h.v;
}

}  // namespace wavetrace
