// The wavefront engine: paths in waves, moved through separate kernels over
// structure-of-arrays queues (see docs/architecture.md). Same estimator, same random numbers
// and same per-vertex code as the megakernel: the same image up to rounding.
#pragma once

#include <cstddef>
#include <vector>

#include "wavetrace/render/film.h"
#include "wavetrace/render/megakernel.h"
#include "wavetrace/render/render.h"

namespace wavetrace {

struct Scene;
class Bvh;

struct WavefrontConfig {
    // Most paths a thread carries through the stages at once (a wave holds one sample of
    // consecutive pixels; the waves shrink towards the end of a pass: wavefront_waves). 4096
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
// The waves a render of `pixels` pixels on `threads` threads is cut into, in the order the
// threads take them: consecutive pixel ranges [first, first + n) of the pass order that cover
// it once, guided self-scheduling (Polychronopoulos & Kuck, 1987): each wave takes a share
// 1 / (2 threads) of the pixels left, at most wave_size and at least 128 (fewer only where
// fewer are left), so waves start large and shrink towards the end of a pass, where the
// threads wait for the last ones.
struct WaveRange {
    size_t first, n;
};
std::vector<WaveRange> wavefront_waves(size_t pixels, size_t threads,
                                       const WavefrontConfig& wavefront);
// The most paths a thread carries at once in such a render: its first wave's size.
size_t wavefront_wave_size(size_t pixels, size_t threads, const WavefrontConfig& wavefront);

}  // namespace wavetrace
