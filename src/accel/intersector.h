// What the engines need from a ray intersector: the closest hit and an occlusion test. Our BVH
// is one; the tests' and benchmarks' Embree mirror (src/embree) is another, so that each
// engine can also run as a plain Embree path tracer. The engines take it as a template
// parameter: no virtual call per ray.
#pragma once

#include <concepts>

#include "wavetrace/accel/bvh.h"
#include "wavetrace/math/ray.h"

namespace wavetrace {

template <class T>
concept Intersector = requires(const T& t, const Ray& ray) {
    { t.intersect(ray) } -> std::same_as<Hit>;
    { t.occluded(ray) } -> std::same_as<bool>;
};

// One that also says which primitive an occlusion test stopped at (our BVH; Embree's
// rtcOccluded1 does not): shadow rays through media use it to skip their closest-hit walk.
template <class T>
concept AnyHitIntersector = Intersector<T> && requires(const T& t, const Ray& ray) {
    { t.any_hit(ray) } -> std::same_as<Hit>;
};

}  // namespace wavetrace
