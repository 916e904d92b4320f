// The reference engine: the seed's recursive ray_color, one path per pixel sample traced to
// its end, parallelized over image tiles.
#pragma once

#include "wavetrace/render/film.h"
#include "wavetrace/render/render.h"
#include "wavetrace/render/stats.h"

namespace wavetrace {

struct Scene;
class Bvh;

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
