// Both engines with Embree as their intersector: the megakernel so built is a plain Embree
// path tracer, the in-house anchor the benchmarks compare our BVH and our wavefront against.
// Same seed, same paths: the images differ from our BVH's only where the two intersectors
// disagree (see the Embree agreement test).
#pragma once

#include "reference/embree_mirror.h"
#include "wavetrace/render/megakernel.h"
#include "wavetrace/render/wavefront.h"

namespace wavetrace {

Film render_megakernel(const Scene& scene,
                       const EmbreeMirror& embree,
                       const RenderConfig& config,
                       RenderStats* stats = nullptr,
                       const ProgressCallback& progress = {});

Film render_wavefront(const Scene& scene,
                      const EmbreeMirror& embree,
                      const RenderConfig& config,
                      const WavefrontConfig& wavefront = {},
                      RenderStats* stats = nullptr,
                      const ProgressCallback& progress = {});

}  // namespace wavetrace
