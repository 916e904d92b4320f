// The one engine-agnostic way to render: a request (settings, engine, sample range) into a
// film, observed from the caller's thread between passes, with cancellation.
#pragma once

#include "wavetrace/render/film.h"
#include "wavetrace/render/render.h"
#include "wavetrace/render/stats.h"
#include "wavetrace/render/wavefront.h"

namespace wavetrace {

struct Scene;
class Bvh;

enum class Engine { Wavefront, Megakernel };

struct RenderRequest {
    // Size, seed, estimator, and the sample range [first_sample, first_sample + spp).
    RenderConfig config;
    Engine engine = Engine::Wavefront;
    WavefrontConfig wavefront;  // the wavefront's wave size
};

// Watches a render. Both callbacks run on the thread that called render(), between passes,
// while no sample is being added: the film may be read (a preview, a checkpoint).
class RenderObserver {
  public:
    virtual ~RenderObserver() = default;
    // Samples per pixel done so far of those requested; return false to stop the render here
    // (every pixel then holds the same number of samples).
    virtual bool on_pass(int samples_done, int samples_requested, const Film& film) = 0;
};

// Renders the request's samples into `film` (of the config's size), after those it holds.
RenderStats render(const Scene& scene,
                   const Bvh& bvh,
                   const RenderRequest& request,
                   Film& film,
                   RenderObserver* observer = nullptr);

}  // namespace wavetrace
