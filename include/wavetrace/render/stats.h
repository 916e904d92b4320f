// What a render reports: its statistics, and the progress callbacks of the engine calls.
#pragma once

#include <cstdint>
#include <functional>

namespace wavetrace {

struct RenderStats {
    double seconds = 0;
    uint64_t paths = 0;  // camera samples
    uint64_t rays = 0;   // every ray traced, shadow rays and medium-boundary steps included
    int spp_done = 0;    // passes completed: samples per pixel added (config.spp unless stopped)
};

// The per-engine calls (render_megakernel, render_wavefront) call this now and then with the
// fraction of the render done, from worker threads. render() in renderer.h reports on the
// caller's thread only.
using ProgressCallback = std::function<void(double fraction)>;

}  // namespace wavetrace
