// The wavefront engine's outer loop: a readable script of kernel launches (pbrt-v4's
// WavefrontPathIntegrator::Render() is the model). The image is cut into waves of consecutive
// pixels that shrink towards the end of a pass (wavefront_waves); the threads take them in
// order, and each thread carries its wave through every
// stage, bounce after bounce and sample after sample of a pass, in queues it reuses from wave to
// wave, so that a wave's queues stay in that core's cache (the per-thread queues of Áfra et
// al., HPG 2016, and of MoonRay, rather than pbrt-v4's one global wave). Generic over the
// intersector: engines/dispatch.h instantiates it for our BVH and for Embree (src/embree).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

#include "accel/intersector.h"
#include "engines/passes.h"
#include "kernels/kernels.h"
#include "shading/trace.h"
#include "util/check.h"
#include "wavetrace/engines/render.h"

namespace wavetrace {

// The waves a render of `pixels` pixels on `threads` threads is cut into, in the order the
// threads take them: consecutive pixel ranges [first, first + n) of the pass order that cover
// it once, guided self-scheduling (Polychronopoulos & Kuck, 1987): each wave takes a share
// 1 / (2 threads) of the pixels left, at most wave_size and at least 128 (fewer only where
// fewer are left), so waves start large and shrink towards the end of a pass, where the
// threads wait for the last ones.
struct WaveRange {
    size_t first, n;
};
std::vector<WaveRange> wavefront_waves(size_t pixels,
                                       size_t threads,
                                       const WavefrontOptions& wavefront);
// The most paths a thread carries at once in such a render: its first wave's size.
size_t wavefront_wave_size(size_t pixels, size_t threads, const WavefrontOptions& wavefront);
namespace wavefront_detail {

// Carries the wave of the pass's pixels [first, first + n) (in pass order) through all its
// bounces and adds its paths to the film; returns the rays traced.
template <Intersector Tracer>
uint64_t run_wave(const WaveInputs& in,
                  const Tracer& bvh,
                  uint32_t sample,
                  uint32_t first,
                  size_t n,
                  bool sort,
                  WaveQueues& q,
                  Film& film) {
    WT_CHECK_LE(n, q.paths.capacity);
    uint64_t rays = 0;
    generate(in, sample, first, 0, n, q.paths, q.rays);
    for (bool camera_rays = true; n > 0; camera_rays = false) {
        if (camera_rays)
            intersect_coherent(bvh, q.rays, 0, n, q.hits);
        else
            intersect(bvh, q.rays, 0, n, q.hits);
        rays += n;
        if (sort) sort_by_material(in.scene, n, q.key, q.paths, q.rays, q.hits);
        const size_t shadows =
            shade(in, sample, q.hits, 0, n, q.paths, q.rays, q.keep, q.shadows, 0);
        WT_DCHECK_LE(shadows, n);  // at most one shadow ray per path per bounce
        rays += intersect_shadow(bvh, in, q.shadows, q.paths, 0, shadows, q.transmittance,
                                 camera_rays ? &q.hits : nullptr);
        mis_combine(q.shadows, q.transmittance, 0, shadows, q.paths);
        accumulate_film(q.paths, q.keep, n, film);
        const size_t left = compact(q.keep, n, q.paths, q.rays);
        WT_DCHECK_LE(left, n);
        n = left;
    }
    return rays;
}

}  // namespace wavefront_detail

template <Intersector Tracer>
RenderStats wavefront(const Scene& scene,
                      const Tracer& bvh,
                      const RenderRequest& request,
                      Film& film,
                      RenderObserver* observer) {
    auto start = std::chrono::steady_clock::now();
    const WavefrontOptions& options = request.wavefront;
    const LightSet lights(scene);
    const CameraRays camera(scene.camera, request.width, request.height);
    const WaveInputs in{scene,
                        lights,
                        request.estimator,
                        request.seed,
                        request.width,
                        request.height,
                        camera,
                        media_at(scene, bvh, scene.camera.look_from)};
    const size_t pixels = static_cast<size_t>(request.width) * request.height;
    // The threads this render may use: the arena's, or fewer under a tbb::global_control limit
    // (--threads). The image depends on neither, so the waves may follow them.
    const size_t threads = static_cast<size_t>(
        std::max(1, std::min<int>(tbb::this_task_arena::max_concurrency(),
                                  static_cast<int>(tbb::global_control::active_value(
                                      tbb::global_control::max_allowed_parallelism)))));
    const std::vector<WaveRange> waves = wavefront_waves(pixels, threads, options);
    tbb::enumerable_thread_specific<WaveQueues> queues([&] {
        WaveQueues q;
        q.resize(waves.empty() ? 1 : waves.front().n);
        return q;
    });
    std::atomic<uint64_t> rays{0};
    std::atomic<uint64_t> paths_done{0};  // pixels times the samples carried for them

    // A pass over all waves: each wave carries its pixels through the pass's samples in order,
    // so every pixel receives its samples in sample order whatever the wave size, the thread
    // count or which thread ran which wave. The waves are taken in their order (one counter),
    // so that the small ones at the end of the schedule are the last to start.
    auto render_pass = [&](uint32_t first_sample, int count) {
        std::atomic<size_t> next{0};
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, threads, 1),
            [&](const tbb::blocked_range<size_t>&) {
                WaveQueues& q = queues.local();
                uint64_t traced = 0;
                for (size_t w; (w = next.fetch_add(1, std::memory_order_relaxed)) < waves.size();) {
                    const WaveRange wave = waves[w];
                    for (uint32_t sample = first_sample; sample < first_sample + uint32_t(count);
                         ++sample)
                        traced += wavefront_detail::run_wave(
                            in, bvh, sample, static_cast<uint32_t>(wave.first), wave.n,
                            options.sort_by_material, q, film);
                    const uint64_t carried = uint64_t(wave.n) * uint64_t(count);
                    const double finished = double(paths_done.fetch_add(carried) + carried);
                    if (observer) observer->on_progress(finished / (double(pixels) * request.spp));
                }
                rays.fetch_add(traced, std::memory_order_relaxed);
            },
            tbb::simple_partitioner());
    };
    const int done = run_passes(request, film, observer, render_pass);

    return render_stats(request, start, done, rays.load());
}

}  // namespace wavetrace
