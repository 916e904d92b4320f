// The wavefront engine: paths in waves, moved through separate kernels over
// structure-of-arrays queues (see docs/architecture.md). Same estimator, same random numbers
// and same per-vertex code as the megakernel: the same image up to rounding.
#pragma once

#include <cstddef>

#include "wavetrace/render/film.h"
#include "wavetrace/render/megakernel.h"
#include "wavetrace/render/render.h"

namespace wavetrace {

struct Scene;
class Bvh;

struct WavefrontConfig {
    // Most paths a thread carries through the stages at once (a wave holds one sample of
    // consecutive pixels; small images are cut into smaller waves, a few per thread). 4096
    // paths keep a wave's queues (wavefront_bytes_per_path() each) within a core's L2 cache.
    size_t wave_size = 4096;
    // Whether each bounce's entries are reordered by material kind before shading (the
    // sort_by_material kernel). Off: shade gathers the vertices its SIMD kernels run over by
    // itself, and the reordering cost 3-6% of the render (docs/benchmarks.md, "Sorting by
    // material"). The image is the same either way.
    bool sort_by_material = false;
};

Film render_wavefront(const Scene& scene,
                      const Bvh& bvh,
                      const RenderConfig& config,
                      const WavefrontConfig& wavefront = {},
                      RenderStats* stats = nullptr,
                      const ProgressCallback& progress = {});
// The same, adding the samples to `film` (of the config's size) after those it holds.
void render_wavefront(const Scene& scene,
                      const Bvh& bvh,
                      const RenderConfig& config,
                      Film& film,
                      const WavefrontConfig& wavefront = {},
                      RenderStats* stats = nullptr,
                      const ProgressCallback& progress = {});

// Queue memory per path in flight, from the queue declarations.
size_t wavefront_bytes_per_path();
// The paths each thread carries at once in a render of `pixels` pixels on `threads` threads:
// wave_size, or less where the image is cut into waves enough to keep every thread busy to the
// end of a pass (at least 64 per thread, of at least 64 paths).
size_t wavefront_wave_size(size_t pixels, size_t threads, const WavefrontConfig& wavefront);

}  // namespace wavetrace
