// The wavefront engine's outer loop: a readable script of kernel launches (pbrt-v4's
// WavefrontPathIntegrator::Render() is the model), in two schedules of the same kernels.
// - resident (the default): the image is cut into waves of consecutive pixels that shrink
//   towards the end of a pass (wavefront_waves); the threads take them in order, and each
//   thread carries its wave through every kernel, bounce after bounce and sample after sample
//   of a pass, in queues it reuses from wave to wave, so that a wave's queues stay in that
//   core's cache (the per-thread queues of Áfra et al., HPG 2016, and of MoonRay).
// - stage: one wave of the pass's pixels at a time, as large as all the threads' waves
//   together, each kernel a tbb::parallel_for over fixed chunks of it (pbrt-v4's CPU wavefront):
//   the threads meet after every kernel, and the queues live in memory rather than in one
//   core's cache.
// Generic over the intersector: engines/dispatch.h instantiates it for our BVH and for Embree
// (src/embree).
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
// The most pixels a wave of a render of `pixels` pixels holds.
size_t wavefront_wave_pixels(size_t pixels, const WavefrontOptions& wavefront);
// The most pixels a thread carries at once in such a render: its first wave's size.
size_t wavefront_wave_size(size_t pixels, size_t threads, const WavefrontOptions& wavefront);
// The most paths a wave of `wave_pixels` pixels carries in a render of `pixels` pixels and
// `spp` samples: as many as the wave size allows, several samples of each pixel where the
// image has fewer pixels than that (the waves of a small image are then as large as a large
// image's, and their paths as coherent: neighbours are samples of one pixel).
size_t wavefront_wave_paths(size_t wave_pixels, size_t pixels, int spp, size_t paths_per_wave);
// The samples per pixel the waves of a render, of at most `wave_pixels` pixels, carry at once
// out of a pass's `count`, in queues of `capacity` paths. (The same for the small waves at the
// end of a pass: they stay small, for balance.)
inline uint32_t wave_samples_per_pixel(size_t wave_pixels, size_t capacity, int count) {
    return static_cast<uint32_t>(
        std::clamp<size_t>(capacity / std::max<size_t>(wave_pixels, 1), 1, size_t(count)));
}
namespace wavefront_detail {

// Carries the wave of the pass's pixels [first, first + pixels) (in pass order), `samples` of
// each, through all its bounces and adds its paths to the film, one thread running every
// kernel; returns the rays traced.
template <Intersector Tracer>
uint64_t run_wave(const WaveInputs& in,
                  const Tracer& bvh,
                  WaveSamples samples,
                  uint32_t first,
                  size_t pixels,
                  bool sort,
                  WaveQueues& q,
                  Film& film) {
    size_t n = pixels * samples.per_pixel;
    WT_CHECK_LE(n, q.paths.capacity);
    uint64_t rays = 0;
    const MisHeuristics heuristics = mis_heuristics(in.estimator, in.lights);
    generate(in, samples, first, 0, n, q.paths, q.rays);
    for (bool camera_rays = true; n > 0; camera_rays = false) {
        if (camera_rays)
            intersect_coherent(bvh, q.rays, 0, n, q.hits);
        else
            intersect(bvh, q.rays, 0, n, q.hits);
        rays += n;
        if (sort) sort_by_material(in.scene, 0, n, q.key, q.paths, q.rays, q.hits);
        const ShadeCounts found =
            shade(in, q.hits, 0, n, q.paths, q.rays, q.keep, q.light_samples, 0, q.emissions, 0);
        const size_t shadows =
            light_sample(in, q.light_samples, 0, found.light_samples, q.shadows, 0, q.paths);
        WT_DCHECK_LE(shadows, n);  // at most one shadow ray per path per bounce
        rays += intersect_shadow(bvh, in, q.shadows, 0, shadows, q.transmittance,
                                 camera_rays ? &q.hits : nullptr);
        mis_combine(in.estimator, heuristics, q.emissions, {0, found.emissions}, q.shadows,
                    q.transmittance, {0, shadows}, q.paths);
        accumulate_film(q.paths, q.keep, 0, n, q.film);
        const size_t left = compact(q.keep, n, q.paths, q.rays);
        WT_DCHECK_LE(left, n);
        n = left;
    }
    add_to_film(in, first, samples, 0, pixels, q.film, film);
    return rays;
}

// The stage schedule's chunks: entries [kStageChunk c, kStageChunk (c + 1)) of the wave, a
// whole number of shade chunks and ray batches. Fixed, so that the queues' order does not depend
// on the thread count (the image does not depend on it either way).
inline constexpr size_t kStageChunk = 1024;

// The stage schedule's wave: the queues, with a second path and ray queue that compaction fills
// (the chunks compact at once, so not in place), and each chunk's counts. Each chunk appends
// to the light-sample, shadow and emission queues from its own first entry, so the chunks need
// no counts of one another's; only compaction adds them up.
struct StageWave {
    WaveQueues q;
    PathQueue next_paths;
    RayQueue next_rays;
    struct ChunkCounts {
        ShadeCounts found;
        size_t shadows = 0, kept = 0, first_kept = 0;
        uint64_t shadow_rays = 0;
    };
    std::vector<ChunkCounts> chunks;

    void resize(size_t n) {
        q.resize(n);
        next_paths.resize(n);
        next_rays.resize(n);
        chunks.resize((n + kStageChunk - 1) / kStageChunk);
    }
};

// body(chunk, begin, end) for each chunk of entries [0, n), in parallel.
template <class Body>
void each_chunk(size_t n, const Body& body) {
    const size_t chunks = (n + kStageChunk - 1) / kStageChunk;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t c = r.begin(); c < r.end(); ++c)
                              body(c, c * kStageChunk, std::min(n, (c + 1) * kStageChunk));
                      });
}

// run_wave's script with each kernel a parallel loop over the wave's chunks.
template <Intersector Tracer>
uint64_t run_wave_in_stages(const WaveInputs& in,
                            const Tracer& bvh,
                            WaveSamples samples,
                            uint32_t first,
                            size_t pixels,
                            bool sort,
                            StageWave& w,
                            Film& film) {
    WaveQueues& q = w.q;
    size_t n = pixels * samples.per_pixel;
    WT_CHECK_LE(n, q.paths.capacity);
    auto& chunk = w.chunks;
    uint64_t rays = 0;
    const MisHeuristics heuristics = mis_heuristics(in.estimator, in.lights);
    each_chunk(n, [&](size_t, size_t b, size_t e) {
        generate(in, samples, first, b, e, q.paths, q.rays);
    });
    for (bool camera_rays = true; n > 0; camera_rays = false) {
        each_chunk(n, [&](size_t, size_t b, size_t e) {
            if (camera_rays)
                intersect_coherent(bvh, q.rays, b, e, q.hits);
            else
                intersect(bvh, q.rays, b, e, q.hits);
        });
        rays += n;
        if (sort)
            each_chunk(n, [&](size_t, size_t b, size_t e) {
                sort_by_material(in.scene, b, e, q.key, q.paths, q.rays, q.hits);
            });
        each_chunk(n, [&](size_t c, size_t b, size_t e) {
            chunk[c].found = shade(in, q.hits, b, e, q.paths, q.rays, q.keep, q.light_samples, b,
                                   q.emissions, b);
        });
        each_chunk(n, [&](size_t c, size_t b, size_t) {
            chunk[c].shadows = light_sample(
                in, q.light_samples, b, b + chunk[c].found.light_samples, q.shadows, b, q.paths);
        });
        each_chunk(n, [&](size_t c, size_t b, size_t) {
            chunk[c].shadow_rays =
                intersect_shadow(bvh, in, q.shadows, b, b + chunk[c].shadows,
                                 q.transmittance, camera_rays ? &q.hits : nullptr);
        });
        each_chunk(n, [&](size_t c, size_t b, size_t) {
            mis_combine(in.estimator, heuristics, q.emissions, {b, b + chunk[c].found.emissions},
                        q.shadows, q.transmittance, {b, b + chunk[c].shadows}, q.paths);
        });
        each_chunk(
            n, [&](size_t, size_t b, size_t e) { accumulate_film(q.paths, q.keep, b, e, q.film); });
        // Compaction as a parallel prefix sum: each chunk counts the paths it keeps, a scan of
        // the chunks' counts gives each chunk where its paths go, and the chunks move them there.
        each_chunk(n, [&](size_t c, size_t b, size_t e) {
            chunk[c].kept = size_t(std::count_if(q.keep.begin() + b, q.keep.begin() + e,
                                                 [](uint8_t k) { return k != 0; }));
        });
        const size_t chunks = (n + kStageChunk - 1) / kStageChunk;
        size_t left = 0;
        for (size_t c = 0; c < chunks; ++c) {
            chunk[c].first_kept = left;
            left += chunk[c].kept;
            rays += chunk[c].shadow_rays;
        }
        each_chunk(n, [&](size_t c, size_t b, size_t e) {
            compact_into(q.keep, b, e, q.paths, q.rays, chunk[c].first_kept, w.next_paths,
                         w.next_rays);
        });
        std::swap(q.paths, w.next_paths);
        std::swap(q.rays, w.next_rays);
        WT_DCHECK_LE(left, n);
        n = left;
    }
    each_chunk(pixels, [&](size_t, size_t b, size_t e) {
        add_to_film(in, first, samples, b, e, q.film, film);
    });
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
    const LightSet lights(scene, request.estimator.strategy == Strategy::Mis);
    const CameraRays camera(scene.camera, request.width, request.height);
    const WaveInputs in{scene,
                        lights,
                        request.estimator,
                        request_sampler(request),
                        request.width,
                        request.height,
                        camera,
                        media_at(scene, bvh, scene.camera.look_from),
                        shadows_walk(scene)};
    const size_t pixels = static_cast<size_t>(request.width) * request.height;
    // The threads this render may use: the arena's, or fewer under a tbb::global_control limit
    // (--threads). The image depends on neither, so the waves may follow them.
    const size_t threads = static_cast<size_t>(
        std::max(1, std::min<int>(tbb::this_task_arena::max_concurrency(),
                                  static_cast<int>(tbb::global_control::active_value(
                                      tbb::global_control::max_allowed_parallelism)))));
    std::atomic<uint64_t> rays{0};
    std::atomic<uint64_t> paths_done{0};  // pixels times the samples carried for them
    auto carried = [&](size_t n, int count) {
        const uint64_t c = uint64_t(n) * uint64_t(count);
        const double finished = double(paths_done.fetch_add(c) + c);
        if (observer) observer->on_progress(finished / (double(pixels) * request.spp));
    };
    const int done = [&] {
        if (options.schedule == Schedule::Stage) {
            // The pass's pixels in consecutive waves of as many paths as the resident
            // schedule's threads hold at once at most.
            const size_t wave = std::min(pixels, threads * wavefront_wave_pixels(pixels, options));
            const size_t capacity =
                wavefront_wave_paths(wave, pixels, request.spp, threads * options.wave_size);
            wavefront_detail::StageWave w;
            w.resize(std::max<size_t>(capacity, 1));
            return run_passes(request, film, observer, [&](uint32_t first_sample, int count) {
                for (size_t first = 0; first < pixels; first += wave) {
                    const size_t n = std::min(wave, pixels - first);
                    const uint32_t per_pixel = wave_samples_per_pixel(wave, capacity, count);
                    const uint32_t end = first_sample + uint32_t(count);
                    for (uint32_t s = first_sample; s < end; s += per_pixel)
                        rays += wavefront_detail::run_wave_in_stages(
                            in, bvh, {s, std::min(per_pixel, end - s)},
                            static_cast<uint32_t>(first), n, options.sort_by_material, w, film);
                    carried(n, count);
                }
            });
        }
        const std::vector<WaveRange> waves = wavefront_waves(pixels, threads, options);
        const size_t capacity = std::max<size_t>(
            1, waves.empty()
                   ? 1
                   : wavefront_wave_paths(waves.front().n, pixels, request.spp, options.wave_size));
        tbb::enumerable_thread_specific<WaveQueues> queues([&] {
            WaveQueues q;
            q.resize(capacity);
            return q;
        });
        // A pass over all waves: each wave carries its pixels through the pass's samples in
        // order, several at once where its queues hold them, so every pixel receives its
        // samples in sample order whatever the wave size, the thread count or which thread ran
        // which wave. The waves are taken in their order (one
        // counter), so that the small ones at the end of the schedule are the last to start.
        return run_passes(request, film, observer, [&](uint32_t first_sample, int count) {
            const uint32_t per_pixel =
                wave_samples_per_pixel(waves.empty() ? 1 : waves.front().n, capacity, count);
            std::atomic<size_t> next{0};
            tbb::parallel_for(
                tbb::blocked_range<size_t>(0, threads, 1),
                [&](const tbb::blocked_range<size_t>&) {
                    WaveQueues& q = queues.local();
                    uint64_t traced = 0;
                    for (size_t w;
                         (w = next.fetch_add(1, std::memory_order_relaxed)) < waves.size();) {
                        const WaveRange wave = waves[w];
                        const uint32_t end = first_sample + uint32_t(count);
                        for (uint32_t s = first_sample; s < end; s += per_pixel)
                            traced += wavefront_detail::run_wave(
                                in, bvh, {s, std::min(per_pixel, end - s)},
                                static_cast<uint32_t>(wave.first), wave.n, options.sort_by_material,
                                q, film);
                        carried(wave.n, count);
                    }
                    rays.fetch_add(traced, std::memory_order_relaxed);
                },
                tbb::simple_partitioner());
        });
    }();

    return render_stats(request, start, done, rays.load());
}

}  // namespace wavetrace
