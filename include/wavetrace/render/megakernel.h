// The reference engine: the seed's recursive ray_color, one path per pixel sample traced to
// its end, parallelized over image tiles.
#pragma once

#include <functional>

#include "wavetrace/render/film.h"
#include "wavetrace/render/render.h"

namespace wavetrace {

struct Scene;
class Bvh;

struct RenderStats {
    double seconds = 0;
    uint64_t paths = 0;  // camera samples
    uint64_t rays = 0;   // every ray traced, shadow rays and medium-boundary steps included
    int spp_done = 0;    // passes completed: samples per pixel added (config.spp unless stopped)
};

// Called now and then from worker threads with the fraction of pixels finished.
using ProgressCallback = std::function<void(double fraction)>;

Film render_megakernel(const Scene& scene,
                       const Bvh& bvh,
                       const RenderConfig& config,
                       RenderStats* stats = nullptr,
                       const ProgressCallback& progress = {});
// The same, adding the samples to `film` (of the config's size) after those it holds.
void render_megakernel(const Scene& scene,
                       const Bvh& bvh,
                       const RenderConfig& config,
                       Film& film,
                       RenderStats* stats = nullptr,
                       const ProgressCallback& progress = {});

}  // namespace wavetrace
