// The wavefront engine's outer loop: a readable script of kernel launches (pbrt-v4's
// WavefrontPathIntegrator::Render() is the model). A pass (one sample of every pixel) is cut
// into waves of consecutive pixels; oneTBB hands the waves to the threads, and each thread
// carries its wave through every stage, bounce after bounce, in queues it reuses from wave to
// wave, so that a wave's queues stay in that core's cache (the per-thread queues of Áfra et
// al., HPG 2016, and of MoonRay, rather than pbrt-v4's one global wave). Generic over the
// intersector: wavefront.cpp instantiates it for our BVH, src/reference for Embree.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>

#include "kernels/kernels.h"
#include "scene/intersector.h"
#include "shading/trace.h"
#include "wavetrace/render/wavefront.h"

namespace wavetrace {
namespace wavefront_detail {

// Waves handed out between two progress reports (on the caller's thread).
constexpr size_t kWavesPerReport = 64;
// Waves per thread and pass that small images are cut into, for balance.
constexpr size_t kWavesPerThread = 4;

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
        rays +=
            intersect_shadow(bvh, in, q.shadows, q.paths, 0, shadows, q.transmittance, camera_rays);
        mis_combine(q.shadows, q.transmittance, 0, shadows, q.paths);
        accumulate_film(q.paths, q.keep, n, film);
        n = compact(q.keep, n, q.paths, q.rays);
    }
    return rays;
}

}  // namespace wavefront_detail

template <Intersector Tracer>
void wavefront(const Scene& scene,
               const Tracer& bvh,
               const RenderConfig& config,
               Film& film,
               const WavefrontConfig& wavefront,
               RenderStats* stats,
               const ProgressCallback& progress) {
    using wavefront_detail::kWavesPerReport, wavefront_detail::kWavesPerThread;
    auto start = std::chrono::steady_clock::now();
    const LightSet lights(scene);
    const CameraRays camera(scene.camera, config.width, config.height);
    const WaveInputs in{scene, lights, config, camera,
                        media_at(scene, bvh, scene.camera.look_from)};
    const size_t pixels = static_cast<size_t>(config.width) * config.height;
    // Small images: waves small enough that every thread gets a few per pass (the image does
    // not depend on the wave size, so this may follow the thread count).
    const size_t threads = static_cast<size_t>(tbb::this_task_arena::max_concurrency());
    const size_t share = (pixels + kWavesPerThread * threads - 1) / (kWavesPerThread * threads);
    const size_t wave_size =
        std::max<size_t>(1, std::min({wavefront.wave_size, pixels, std::max<size_t>(share, 64)}));
    const size_t waves = (pixels + wave_size - 1) / wave_size;
    tbb::enumerable_thread_specific<WaveQueues> queues([&] {
        WaveQueues q;
        q.resize(wave_size);
        return q;
    });
    std::atomic<uint64_t> rays{0};

    // Passes run in order and a stop is only taken between them, so every pixel has the same
    // number of samples, received in sample order: the image does not depend on the wave
    // size, the thread count or which thread ran which wave.
    int done = 0;
    for (; done < config.spp; ++done) {
        if (config.stop && config.stop(done)) break;
        const uint32_t sample = static_cast<uint32_t>(config.first_sample + done);
        for (size_t w0 = 0; w0 < waves; w0 += kWavesPerReport) {
            const size_t w1 = std::min(waves, w0 + kWavesPerReport);
            tbb::parallel_for(
                tbb::blocked_range<size_t>(w0, w1, 1), [&](const tbb::blocked_range<size_t>& r) {
                    WaveQueues& q = queues.local();
                    uint64_t traced = 0;
                    for (size_t w = r.begin(); w < r.end(); ++w) {
                        const size_t first = w * wave_size;
                        const size_t n = std::min(wave_size, pixels - first);
                        traced += wavefront_detail::run_wave(in, bvh, sample,
                                                             static_cast<uint32_t>(first), n,
                                                             wavefront.sort_by_material, q, film);
                    }
                    rays.fetch_add(traced, std::memory_order_relaxed);
                });
            if (progress)
                progress((double(done) * waves + double(w1)) / (double(config.spp) * waves));
        }
    }

    if (stats) {
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->paths = static_cast<uint64_t>(pixels) * done;
        stats->rays = rays.load();
        stats->spp_done = done;
    }
}

}  // namespace wavetrace
