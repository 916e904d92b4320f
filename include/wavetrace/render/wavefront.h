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
    // Paths in flight per wave (at most one sample per pixel, so clamped to the pixel count).
    // 2^16 paths keep the queues near 20 MiB: within a large L3 cache.
    size_t wave_size = 1 << 16;
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

}  // namespace wavetrace
