#include "ray_batches.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

#include "embree/embree_mirror.h"
#include "results.h"
#include "sampling/warp.h"
#include "shading/lights.h"
#include "shading/path_vertex.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

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
        LightSample ls = lights.sample(scene, o, lights.select(sample_1d(7, i, 0, 2), o, n),
                                       sample_1d(7, i, 0, 3), sample_1d(7, i, 0, 4));
        if (ls.valid) b.shadow.push_back(Ray{o, ls.wi, 0.0f, ls.dist * (1.0f - 1e-4f)});
    }
    return b;
}

namespace {

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

}  // namespace

std::vector<std::vector<double>> interleaved(const std::vector<Ray>& rays,
                                             int threads,
                                             const std::vector<Tracer>& tracers,
                                             int rounds) {
    std::vector<std::vector<double>> runs(rounds);
    for (auto& round : runs)
        for (const Tracer& t : tracers) round.push_back(mrays_once(rays, threads, t));
    return runs;
}

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

BatchRates time_batch(const Bvh& bvh,
                      const EmbreeMirror& embree,
                      const std::vector<Ray>& rays,
                      bool shadow,
                      bool packets,
                      int threads,
                      int rounds) {
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
        // A 4 x 2 pixel tile (4 rays each on SSE4/NEON) against Embree's 8- and 16-wide.
        tracers.push_back({8, [&](size_t i) {
                               bvh.intersect_packet(std::span(&rays[i], 8), std::span(&hits[i], 8));
                           }});
        tracers.push_back({8, [&](size_t i) { embree.intersect_packet(&rays[i], 8); }});
        tracers.push_back({16, [&](size_t i) { embree.intersect_packet(&rays[i], 16); }});
    }
    const auto runs = interleaved(rays, threads, tracers, rounds);
    BatchRates r;
    r.ours = median_rate(runs, 0);
    r.embree = median_rate(runs, 1);
    r.ours_over_embree = median_ratio(runs, 0, 1);
    if (packets) {
        r.packets = true;
        r.ours_packet = median_rate(runs, 2);
        r.embree_packet8 = median_rate(runs, 3);
        r.embree_packet16 = median_rate(runs, 4);
        r.ours_packet_over_embree16 = median_ratio(runs, 2, 4);
    }
    return r;
}

void time_batches(const Bvh& bvh,
                  const EmbreeMirror& embree,
                  const Batches& b,
                  int threads,
                  int rounds,
                  const std::function<void(const char*, size_t, const BatchRates&)>& report) {
    report("primary", b.primary.size(),
           time_batch(bvh, embree, b.primary, false, true, threads, rounds));
    report("diffuse", b.diffuse.size(),
           time_batch(bvh, embree, b.diffuse, false, false, threads, rounds));
    report("shadow", b.shadow.size(),
           time_batch(bvh, embree, b.shadow, true, false, threads, rounds));
}

double median_ms(const std::function<double()>& build, int times) {
    std::vector<double> t;
    for (int i = 0; i < times; ++i) t.push_back(build());
    return spread(t).median;
}

}  // namespace wavetrace::bench
