// How both engines cut a render into passes of samples over every pixel. A pass boundary is
// where an observer may read the film or stop the render: nothing is being added then, and
// every pixel holds the same number of samples. Each pixel still receives its samples in
// order, so the image does not depend on how the samples were split.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "wavetrace/engines/render.h"

namespace wavetrace {

// Calls render_pass(first_sample, count) until the request's samples are done or the observer
// stops the render or the time limit is reached; returns the samples per pixel done. Without an
// observer or a time limit the render is one pass (the threads meet once, at the end); with
// one, the first pass is one sample and the later ones last about request.pass_seconds.
template <class RenderPass>
int run_passes(const RenderRequest& request,
               const Film& film,
               RenderObserver* observer,
               RenderPass&& render_pass) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point begin = Clock::now();
    const bool in_passes = observer || request.time_limit > 0;
    int done = 0, chunk = 1;
    while (done < request.spp) {
        if (observer && !observer->on_pass(done, request.spp, film)) break;
        if (request.time_limit > 0 && done > 0 &&
            std::chrono::duration<double>(Clock::now() - begin).count() >= request.time_limit)
            break;
        const int count = in_passes ? std::min(chunk, request.spp - done) : request.spp - done;
        const auto start = Clock::now();
        render_pass(static_cast<uint32_t>(request.first_sample + done), count);
        done += count;
        const double seconds =
            std::chrono::duration<double>(Clock::now() - start).count();
        chunk = static_cast<int>(
            std::clamp(count * request.pass_seconds / std::max(seconds, 1e-3), 1.0, 65536.0));
    }
    // The last pass is reported too: the observer sees the finished film.
    if (observer && done == request.spp) observer->on_pass(done, request.spp, film);
    return done;
}

// What a render of `done` samples per pixel that started at `start` reports.
inline RenderStats render_stats(const RenderRequest& request,
                                std::chrono::steady_clock::time_point start,
                                int done,
                                uint64_t rays) {
    RenderStats stats;
    stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    stats.paths = static_cast<uint64_t>(request.width) * request.height * done;
    stats.rays = rays;
    stats.spp_done = done;
    return stats;
}

}  // namespace wavetrace
