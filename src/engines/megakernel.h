// The megakernel: per pixel sample, a recursive ray_color in the seed's style (depth-limited,
// with Russian roulette). Every step of a path is a call into shading/path_vertex.h, the code
// the wavefront kernels call too. Generic over the intersector: megakernel.cpp instantiates it
// for our BVH, src/reference for Embree.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>

#include "scene/intersector.h"
#include "shading/path_vertex.h"
#include "shading/trace.h"
#include "wavetrace/render/megakernel.h"
#include "wavetrace/render/sampler.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace megakernel_detail {

constexpr int kTile = 16;

template <Intersector Tracer>
struct PathContext {
    const Scene& scene;
    const Tracer& bvh;
    const LightSet& lights;
    const RenderConfig& config;
    uint32_t pixel;
    uint32_t sample;
    uint64_t rays = 0;
};

// Radiance arriving along `ray` (the seed's ray_color). `bounce` numbers the vertex the ray
// will reach: 0 for camera rays. `beta` is the path throughput so far, for Russian roulette.
template <Intersector Tracer>
Color ray_color(PathContext<Tracer>& ctx,
                Ray ray,
                int bounce,
                MediumStack media,
                const PreviousVertex& prev,
                Color beta) {
    const RenderConfig& cfg = ctx.config;
    float flight = segment_flight(ctx.scene, cfg.seed, ctx.pixel, ctx.sample, bounce);
    for (int crossing = 0; crossing < kMaxBoundaryCrossings; ++crossing) {
        ++ctx.rays;
        Hit hit = ctx.bvh.intersect(ray);
        SegmentResult seg =
            resolve_segment(ctx.scene, ctx.lights, cfg, ray, hit, media, flight, prev);
        switch (seg.event) {
            case SegmentEvent::Cross:
                ray = seg.next;
                continue;
            case SegmentEvent::Emission:
                return seg.emission;
            case SegmentEvent::End:
                return {};
            case SegmentEvent::Scatter:
                break;
        }
        if (!may_scatter(cfg, bounce)) return seg.emission;
        const Vertex& v = seg.vertex;
        VertexSamples u = vertex_samples(cfg.seed, ctx.pixel, ctx.sample, bounce);

        // Next-event estimation: a shadow ray to a light sample, weighted for the strategy.
        Color radiance = seg.emission;  // zero but at an emitter that also reflects
        const WeightedDirect d = next_event(ctx.scene, ctx.lights, cfg, v, seg.wo, u);
        if (d.weight > 0.0f)
            radiance +=
                d.sample.value *
                (d.weight * transmittance(ctx.scene, ctx.bvh, d.sample.shadow, media, &ctx.rays));

        // The continuation, recursively.
        PathStep step = continue_path(ctx.scene, ctx.lights, cfg, v, seg.wo, bounce, beta, media,
                                      u.continuation, u.roulette);
        if (!step.alive) return radiance;
        return radiance + step.weight * ray_color(ctx, step.next, bounce + 1, media, step.prev,
                                                  beta * step.weight);
    }
    return {};
}

}  // namespace megakernel_detail

template <Intersector Tracer>
void megakernel(const Scene& scene,
                const Tracer& bvh,
                const RenderConfig& config,
                Film& film,
                RenderStats* stats,
                const ProgressCallback& progress) {
    using megakernel_detail::kTile;
    auto start = std::chrono::steady_clock::now();
    LightSet lights(scene);
    CameraRays camera(scene.camera, config.width, config.height);
    const MediumStack camera_media = media_at(scene, bvh, scene.camera.look_from);
    const int tiles_x = (config.width + kTile - 1) / kTile;
    const int tiles_y = (config.height + kTile - 1) / kTile;
    const int tiles = tiles_x * tiles_y;
    std::atomic<uint64_t> rays{0};
    std::atomic<int64_t> tiles_done{0};  // tile passes, weighted by their sample counts

    // Passes of samples over all tiles: a stop between passes leaves every pixel with the same
    // number of samples, and each pixel still receives its samples in order, so the image does
    // not depend on how the samples were split. Without a stop function the render is one
    // pass; with one, passes last about config.pass_seconds (half a second): long enough that a
    // tile keeps its samples together (its part of the BVH stays in cache), short enough to stop
    // promptly.
    int done = 0, chunk = 1;
    while (done < config.spp) {
        if (config.stop && config.stop(done)) break;
        const int count = config.stop ? std::min(chunk, config.spp - done) : config.spp - done;
        const uint32_t first = static_cast<uint32_t>(config.first_sample + done);
        const auto pass_start = std::chrono::steady_clock::now();
        tbb::parallel_for(tbb::blocked_range<int>(0, tiles), [&](const tbb::blocked_range<int>& r) {
            for (int tile = r.begin(); tile < r.end(); ++tile) {
                const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
                uint64_t tile_rays = 0;
                for (int y = y0; y < std::min(y0 + kTile, config.height); ++y)
                    for (int x = x0; x < std::min(x0 + kTile, config.width); ++x) {
                        const uint32_t pixel = static_cast<uint32_t>(y) * config.width + x;
                        for (uint32_t sample = first; sample < first + uint32_t(count); ++sample) {
                            megakernel_detail::PathContext<Tracer> ctx{scene,  bvh,   lights,
                                                                       config, pixel, sample};
                            Ray ray = generate_camera_ray(camera, config.seed, pixel, sample, x, y);
                            Color c = megakernel_detail::ray_color(
                                ctx, ray, 0, camera_media, PreviousVertex{ray.o}, Color(1.0f));
                            film.add(static_cast<int>(pixel), c);
                            tile_rays += ctx.rays;
                        }
                    }
                rays.fetch_add(tile_rays, std::memory_order_relaxed);
                const double finished = tiles_done.fetch_add(count) + count;
                if (progress) progress(finished / (double(tiles) * config.spp));
            }
        });
        done += count;
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_start).count();
        chunk = static_cast<int>(
            std::clamp(count * config.pass_seconds / std::max(seconds, 1e-3), 1.0, 65536.0));
    }

    if (stats) {
        stats->seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->paths = static_cast<uint64_t>(config.width) * config.height * done;
        stats->rays = rays.load();
        stats->spp_done = done;
    }
}

}  // namespace wavetrace
