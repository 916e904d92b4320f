// Our BVH against Embree on the same captured ray batches: coherent primary rays, incoherent
// diffuse bounces, and shadow rays; single rays on one thread and on all threads, Embree's
// 8- and 16-wide packets on the primary batch; and build times. Each row times its tracers in
// interleaved rounds and reports medians, the ratios as medians of the rounds' ratios.
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <functional>

#include "embree/embree_mirror.h"
#include "sampling/warp.h"
#include "sections.h"
#include "shading/lights.h"
#include "shading/path_vertex.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

namespace {

struct Batches {
    std::vector<Ray> primary, diffuse, shadow;
};

// Primary rays in 4 x 2 pixel tiles (so that 8 consecutive rays form a coherent packet and 16
// form two), then from each primary hit a cosine-distributed bounce and a shadow ray to a
// light sample.
Batches capture(const Scene& scene, const Bvh& bvh, int side) {
    Batches b;
    CameraRays camera(scene.camera, side, side);
    LightSet lights(scene);
    for (int ty = 0; ty < side; ty += 2)
        for (int tx = 0; tx < side; tx += 4)
            for (int y = ty; y < ty + 2; ++y)
                for (int x = tx; x < tx + 4; ++x)
                    b.primary.push_back(camera.generate(x + 0.5f, y + 0.5f, 0.5f, 0.5f));
    uint32_t i = 0;
    for (const Ray& ray : b.primary) {
        ++i;
        Hit hit = bvh.intersect(ray);
        if (!hit.found()) continue;
        SurfaceHit s = surface_at(scene, ray, hit);
        Normal3 n = s.front_face ? s.ng : -s.ng;
        Vec3 local = sample_cosine_hemisphere(sample_1d(7, i, 0, 0), sample_1d(7, i, 0, 1));
        Point3 o = s.p + origin_offset(s.p) * n;
        b.diffuse.push_back(Ray{o, Frame::from_normal(n).to_world(local)});
        if (lights.empty()) continue;
        LightSample ls = lights.sample(scene, o, lights.select(sample_1d(7, i, 0, 2)),
                                       sample_1d(7, i, 0, 3), sample_1d(7, i, 0, 4));
        if (ls.valid) b.shadow.push_back(Ray{o, ls.wi, 0.0f, ls.dist * (1.0f - 1e-4f)});
    }
    return b;
}

// How a batch is traced: `step` rays per call of `trace(first ray)`.
struct Tracer {
    size_t step;
    std::function<void(size_t)> trace;
};

// Mrays/s of one pass of `t` over all rays; `threads` 1 runs serially.
double mrays_once(const std::vector<Ray>& rays, int threads, const Tracer& t) {
    const size_t calls = rays.size() / t.step;
    auto start = std::chrono::steady_clock::now();
    if (threads == 1) {
        for (size_t k = 0; k < calls; ++k) t.trace(k * t.step);
    } else {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, calls, 64),
                          [&](const tbb::blocked_range<size_t>& r) {
                              for (size_t k = r.begin(); k < r.end(); ++k) t.trace(k * t.step);
                          });
    }
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return double(calls * t.step) / s * 1e-6;
}

// Passes of every tracer over the same rays, interleaved (A B C A B C ...) so that a shared
// machine's drift falls on all of them alike: runs[k][j] is tracer j's Mrays/s in round k.
std::vector<std::vector<double>> interleaved(const std::vector<Ray>& rays,
                                             int threads,
                                             const std::vector<Tracer>& tracers,
                                             int rounds) {
    std::vector<std::vector<double>> runs(rounds);
    for (auto& round : runs)
        for (const Tracer& t : tracers) round.push_back(mrays_once(rays, threads, t));
    return runs;
}

// Tracer j's median rate, and the median over rounds of tracer a's rate over tracer b's.
double median_rate(const std::vector<std::vector<double>>& runs, size_t j) {
    std::vector<double> v;
    for (const auto& round : runs) v.push_back(round[j]);
    return spread(v).median;
}
double median_ratio(const std::vector<std::vector<double>>& runs, size_t a, size_t b) {
    std::vector<double> v;
    for (const auto& round : runs) v.push_back(round[a] / round[b]);
    return spread(v).median;
}

double median_ms(const std::function<double()>& build) {
    std::vector<double> t;
    for (int i = 0; i < 3; ++i) t.push_back(build());
    return spread(t).median;
}

}  // namespace

void bench_bvh(const Options& o, Results& r) {
    r.table("bvh", {"scene", "batch", "threads", "rays", "ours_mrays", "embree_mrays",
                    "ours_over_embree", "embree_packet8_mrays", "embree_packet16_mrays",
                    "ours_packet_mrays", "ours_packet_over_embree_packet16"});
    r.table("bvh_build", {"scene", "primitives", "ours_ms", "embree_medium_ms", "embree_high_ms"});
    const int all_threads = tbb::this_task_arena::max_concurrency();
    for (const char* name : {"cornell", "everything", "dragon"}) {
        Scene scene = load_scene(o.scenes / (std::string(name) + ".json"));
        Bvh bvh = Bvh::build(scene);
        EmbreeMirror embree(scene, RTC_BUILD_QUALITY_MEDIUM, /*robust=*/false);
        Batches b = capture(scene, bvh, o.quick ? 32 : 512);
        for (int threads : {1, all_threads}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            auto row = [&](const char* batch, const std::vector<Ray>& rays, bool shadow,
                           bool packets) {
                // Ours and Embree's single rays; on coherent batches also our 8-ray packets
                // (a 4 x 2 pixel tile; 4 rays each on SSE4/NEON) and Embree's 8- and 16-wide.
                std::vector<Hit> hits(rays.size());
                std::vector<Tracer> tracers{{1,
                                             [&](size_t i) {
                                                 if (shadow)
                                                     (void)bvh.occluded(rays[i]);
                                                 else
                                                     (void)bvh.intersect(rays[i]);
                                             }},
                                            {1, [&](size_t i) {
                                                 if (shadow)
                                                     (void)embree.occluded(rays[i]);
                                                 else
                                                     (void)embree.intersect(rays[i]);
                                             }}};
                if (packets) {
                    tracers.push_back({8, [&](size_t i) {
                                           bvh.intersect_packet(std::span(&rays[i], 8),
                                                                std::span(&hits[i], 8));
                                       }});
                    tracers.push_back({8, [&](size_t i) { embree.intersect_packet(&rays[i], 8); }});
                    tracers.push_back(
                        {16, [&](size_t i) { embree.intersect_packet(&rays[i], 16); }});
                }
                const auto runs = interleaved(rays, threads, tracers, o.repetitions());
                const double ours = median_rate(runs, 0), ref = median_rate(runs, 1);
                const double ratio = median_ratio(runs, 0, 1);
                nlohmann::json p8 = nullptr, p16 = nullptr, ours_p = nullptr, ratio_p = nullptr;
                if (packets) {
                    ours_p = median_rate(runs, 2);
                    p8 = median_rate(runs, 3);
                    p16 = median_rate(runs, 4);
                    ratio_p = median_ratio(runs, 2, 4);
                    std::printf(
                        "bvh %-10s packets  %d thread(s): ours %7.2f Mrays/s, embree "
                        "16-wide %7.2f, ours/embree %.2f\n",
                        name, threads, double(ours_p), double(p16), double(ratio_p));
                }
                r.row("bvh", {name, batch, threads, rays.size(), ours, ref, ratio, p8, p16, ours_p,
                              ratio_p});
                std::printf(
                    "bvh %-10s %-8s %d thread(s): ours %7.2f Mrays/s, embree %7.2f, ours/embree "
                    "%.2f\n",
                    name, batch, threads, ours, ref, ratio);
                std::fflush(stdout);
            };
            row("primary", b.primary, false, true);
            row("diffuse", b.diffuse, false, false);
            row("shadow", b.shadow, true, false);
        }
        double ours = median_ms([&] { return Bvh::build(scene).stats().build_ms; });
        double medium = median_ms(
            [&] { return EmbreeMirror(scene, RTC_BUILD_QUALITY_MEDIUM, false).build_ms(); });
        double high = median_ms(
            [&] { return EmbreeMirror(scene, RTC_BUILD_QUALITY_HIGH, false).build_ms(); });
        r.row("bvh_build", {name, scene.primitive_count(), ours, medium, high});
    }
}

}  // namespace wavetrace::bench
