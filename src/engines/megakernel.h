// The megakernel: per pixel sample, a recursive ray_color in the style of *Ray Tracing in One
// Weekend* (depth-limited, with Russian roulette). Every step of a path is a call into
// shading/path_vertex.h, the code the wavefront kernels call too. Generic over the intersector:
// engines/dispatch.h instantiates it for our BVH and for Embree (src/embree).
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>

#include "accel/intersector.h"
#include "engines/passes.h"
#include "sampling/sampler.h"
#include "shading/path_vertex.h"
#include "shading/trace.h"
#include "wavetrace/engines/render.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace megakernel_detail {

constexpr int kTile = 16;

template <Intersector Tracer>
struct PathContext {
    const Scene& scene;
    const Tracer& bvh;
    const LightSet& lights;
    const Estimator& estimator;
    MisHeuristics heuristics;  // mis_heuristics(estimator, lights)
    Sampler sampler;
    uint32_t pixel;
    uint32_t sample;
    bool shadows_walk;  // shadows_walk(scene)
    uint64_t rays = 0;
};

// Radiance arriving along `ray` (the book's ray_color). `bounce` numbers the vertex the ray
// will reach (0 for camera rays), `depth` is that vertex's depth (path_vertex.h: thin sheets
// passed do not count). `beta` is the path throughput so far and `eta_scale` the path's
// (path_vertex.h), for Russian roulette. `flight` is the optical depth the ray may travel in
// media before it scatters (segment_flight of `bounce`).
template <Intersector Tracer>
Color ray_color(PathContext<Tracer>& ctx,
                Ray ray,
                int bounce,
                int depth,
                MediumStack media,
                const PreviousVertex& prev,
                Color beta,
                float eta_scale,
                float flight) {
    const Estimator& cfg = ctx.estimator;
    Color flight_weight(1.0f);  // the segments' weights (chromatic media), from the ray's start
    for (int crossing = 0; crossing < kMaxBoundaryCrossings; ++crossing) {
        ++ctx.rays;
        Hit hit = ctx.bvh.intersect(ray);
        SegmentResult seg =
            resolve_segment(ctx.scene, ctx.lights, cfg, ray, hit, media, flight, prev);
        flight_weight = flight_weight * seg.weight;
        // Emission found, weighted for the strategy (zero but on an emitter or in the
        // background, or at an emitter that also reflects).
        const Color emission =
            max_component(seg.emission) > 0.0f
                ? flight_weight * seg.emission *
                      emission_weight(cfg.strategy, ctx.heuristics.of(seg.at_infinity),
                                      prev.counts_fully, prev.pdf_bsdf, seg.emission_pdf_light)
                : Color(0.0f);
        switch (seg.event) {
            case SegmentEvent::Cross:
                ray = seg.next;
                continue;
            case SegmentEvent::Emission:
                return emission;
            case SegmentEvent::End:
                return {};
            case SegmentEvent::Scatter:
                break;
        }
        const Vertex& v = seg.vertex;
        if (!may_continue(cfg, v, depth)) return emission;
        // Without media no segment reads a flight (segment_flight), so none is drawn.
        float next_flight = 0.0f;
        VertexSamples u = vertex_samples(ctx.sampler, ctx.pixel, ctx.sample, bounce,
                                         reads_one_sample_pairs(cfg.strategy),
                                         ctx.scene.media.empty() ? nullptr : &next_flight);
        beta = beta * flight_weight;

        // Next-event estimation: a shadow ray to a light sample, weighted for the strategy.
        Color radiance = emission;
        const DirectSample d = next_event(ctx.scene, ctx.lights, cfg, v, seg.wo, u);
        if (d.valid) {
            const float w =
                direct_weight(cfg.strategy, ctx.heuristics.of(std::isinf(d.shadow.tmax)),
                              d.pdf_light, d.pdf_bsdf);
            if (w > 0.0f)
                radiance +=
                    flight_weight * d.value *
                    (w * transmittance(ctx.scene, ctx.bvh, d.shadow,
                                       ctx.shadows_walk
                                           ? shadow_media(ctx.scene.medium_boundaries, media,
                                                          v.interior, v.ng, seg.wo, d.shadow.d)
                                           : media,
                                       ctx.shadows_walk, &ctx.rays));
        }

        // The continuation, recursively.
        PathStep step = continue_path(ctx.scene, ctx.lights, cfg, v, seg.wo, prev, depth, beta,
                                      eta_scale, media, u.continuation, u.roulette);
        if (!step.passed_sheet) step.prev.select_total = d.select_total;
        const int next_depth = wavetrace::next_depth(bounce, depth, step);
        if (!step.alive || !ray_may_bring_light(cfg, ctx.lights, next_depth)) return radiance;
        const Color weight = flight_weight * step.weight;
        return radiance + weight * ray_color(ctx, step.next, bounce + 1, next_depth, media,
                                             step.prev, beta * step.weight, step.eta_scale,
                                             next_flight);
    }
    return {};
}

}  // namespace megakernel_detail

template <Intersector Tracer>
RenderStats megakernel(const Scene& scene,
                       const Tracer& bvh,
                       const RenderRequest& request,
                       Film& film,
                       RenderObserver* observer) {
    using megakernel_detail::kTile;
    auto start = std::chrono::steady_clock::now();
    LightSet lights(scene, request.estimator.strategy == Strategy::Mis);
    const MisHeuristics heuristics = mis_heuristics(request.estimator, lights);
    CameraRays camera(scene.camera, request.width, request.height);
    const MediumStack camera_media = media_at(scene, bvh, scene.camera.look_from);
    const bool shadows_walk = wavetrace::shadows_walk(scene);
    const int width = request.width, height = request.height;
    const Sampler sampler = request_sampler(request);
    const int tiles_x = (width + kTile - 1) / kTile;
    const int tiles_y = (height + kTile - 1) / kTile;
    const int tiles = tiles_x * tiles_y;
    std::atomic<uint64_t> rays{0};
    std::atomic<int64_t> tiles_done{0};  // tile passes, weighted by their sample counts

    // A pass over all tiles, each tile's pixels carrying their samples [first, first + count)
    // in order: a tile keeps its samples together, so its part of the BVH stays in cache.
    auto render_pass = [&](uint32_t first, int count) {
        tbb::parallel_for(tbb::blocked_range<int>(0, tiles), [&](const tbb::blocked_range<int>& r) {
            for (int tile = r.begin(); tile < r.end(); ++tile) {
                const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
                uint64_t tile_rays = 0;
                for (int y = y0; y < std::min(y0 + kTile, height); ++y)
                    for (int x = x0; x < std::min(x0 + kTile, width); ++x) {
                        const uint32_t pixel = static_cast<uint32_t>(y) * width + x;
                        for (uint32_t sample = first; sample < first + uint32_t(count); ++sample) {
                            megakernel_detail::PathContext<Tracer> ctx{
                                scene,   bvh,   lights, request.estimator, heuristics,
                                sampler, pixel, sample, shadows_walk};
                            Ray ray = generate_camera_ray(camera, sampler, pixel, sample, x, y);
                            Color c = megakernel_detail::ray_color(
                                ctx, ray, 0, 0, camera_media, PreviousVertex{ray.o}, Color(1.0f),
                                1.0f, segment_flight(scene, sampler, pixel, sample, 0));
                            film.add(static_cast<int>(pixel), c);
                            tile_rays += ctx.rays;
                        }
                    }
                rays.fetch_add(tile_rays, std::memory_order_relaxed);
                const double finished = tiles_done.fetch_add(count) + count;
                if (observer) observer->on_progress(finished / (double(tiles) * request.spp));
            }
        });
    };
    const int done = run_passes(request, film, observer, render_pass);

    return render_stats(request, start, done, rays.load());
}

}  // namespace wavetrace
