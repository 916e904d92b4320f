// What the engines need from a ray intersector: the closest hit and an occlusion test. Our BVH
// is one; the tests' and benchmarks' Embree mirror (src/reference) is another, so that each
// engine can also run as a plain Embree path tracer. The engines take it as a template
// parameter: no virtual call per ray.
#pragma once

#include <concepts>

#include "wavetrace/math/ray.h"
#include "wavetrace/scene/bvh.h"

namespace wavetrace {

template <class T>
concept Intersector = requires(const T& t, const Ray& ray) {
    { t.intersect(ray) } -> std::same_as<Hit>;
    { t.occluded(ray) } -> std::same_as<bool>;
};

}  // namespace wavetrace
