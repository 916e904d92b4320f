// Both engines with Embree as their intersector: the megakernel so built is a plain Embree
// path tracer, the in-house anchor the benchmarks compare our BVH and our wavefront against.
// Same seed, same paths: the images differ from our BVH's only where the two intersectors
// disagree (see the Embree agreement test).
#pragma once

#include "embree/embree_mirror.h"
#include "wavetrace/engines/render.h"

namespace wavetrace {

// render() of wavetrace/engines/render.h, the request's engine tracing rays with Embree.
RenderStats render(const Scene& scene,
                   const EmbreeMirror& embree,
                   const RenderRequest& request,
                   Film& film,
                   RenderObserver* observer = nullptr);

}  // namespace wavetrace
