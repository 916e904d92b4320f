// The wavefront engine's outer loop: a readable script of kernel launches (pbrt-v4's
// WavefrontPathIntegrator::Render() is the model). Each stage runs over its queue with a thin
// oneTBB parallel_for; queues are compacted after every bounce. Generic over the intersector:
// wavefront.cpp instantiates it for our BVH, src/reference for Embree.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>

#include "kernels/kernels.h"
#include "queues/compact.h"
#include "shading/trace.h"
#include "wavetrace/render/wavefront.h"
#include "wavetrace/scene/intersector.h"

namespace wavetrace {
namespace wavefront_detail {
constexpr size_t kGrain = 256;

// The thin wrapper that runs a range kernel on all threads.
template <class Kernel>
void launch(size_t n, Kernel&& kernel) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, kGrain),
                      [&](const tbb::blocked_range<size_t>& r) { kernel(r.begin(), r.end()); });
}

// Copies the kept entries of `from` to the front of `to`, in order; returns their count.
template <class Queue>
size_t compact_into(const Queue& from,
                    Queue& to,
                    std::span<const uint8_t> keep,
                    std::vector<uint32_t>& indices) {
    size_t n = stable_compact(keep, indices);
    launch(n, [&](size_t b, size_t e) {
        for (size_t k = b; k < e; ++k) to.copy_from(k, from, indices[k]);
    });
    return n;
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
    using wavefront_detail::compact_into, wavefront_detail::kGrain, wavefront_detail::launch;
    auto start = std::chrono::steady_clock::now();
    const LightSet lights(scene);
    const CameraRays camera(scene.camera, config.width, config.height);
    const WaveInputs in{scene, lights, config, camera,
                        media_at(scene, bvh, scene.camera.look_from)};
    const uint64_t pixels = static_cast<uint64_t>(config.width) * config.height;
    const uint64_t total = pixels * static_cast<uint64_t>(config.spp);
    const size_t wave_size = std::max<size_t>(1, std::min<uint64_t>(wavefront.wave_size, pixels));
    WaveQueues q;
    q.resize(wave_size);
    uint64_t rays = 0;

    // Waves run in sample order and never straddle two passes (one sample of every pixel), so
    // a stop between passes leaves every pixel with the same number of samples: the loop only
    // ends at a pass boundary, so first / pixels passes are done.
    uint64_t first = 0;
    while (first < total) {
        if (first % pixels == 0 && config.stop && config.stop()) break;
        const uint64_t pass_end = (first / pixels + 1) * pixels;
        const size_t slots = static_cast<size_t>(std::min<uint64_t>(wave_size, pass_end - first));
        launch(slots, [&](size_t b, size_t e) { generate(in, q, first, b, e); });
        size_t n = slots;
        while (n > 0) {
            launch(n, [&](size_t b, size_t e) { intersect(bvh, q, b, e); });
            rays += n;
            bucket_by_material(in, q, n);
            launch(n, [&](size_t b, size_t e) { shade(in, q, b, e); });
            launch(n, [&](size_t b, size_t e) { light_sample(in, q, b, e); });
            size_t shadows = compact_into(q.shadow_candidates, q.shadow,
                                          std::span(q.shadow_keep.data(), n), q.compacted);
            rays += tbb::parallel_reduce(
                tbb::blocked_range<size_t>(0, shadows, kGrain), uint64_t{0},
                [&](const tbb::blocked_range<size_t>& r, uint64_t acc) {
                    return acc + intersect_shadow(bvh, in, q, r.begin(), r.end());
                },
                [](uint64_t a, uint64_t b) { return a + b; });
            launch(shadows, [&](size_t b, size_t e) { mis_combine(in, q, b, e); });
            n = compact_into(q.rays, q.next_rays, std::span(q.keep.data(), n), q.compacted);
            std::swap(q.rays, q.next_rays);
        }
        accumulate_film(q, film, slots);
        first += slots;
        if (progress) progress(double(first) / double(total));
    }

    if (stats) {
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->paths = first;
        stats->rays = rays;
        stats->spp_done = static_cast<int>(first / pixels);
    }
}

}  // namespace wavetrace
