// The sections of the benchmark suite. Each measures side by side in one process and adds its
// tables to the results.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "results.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

// Interleaved repetitions of each measurement that the engines, scaling and BVH sections take
// medians of: five, since with three single rows moved by up to ±5% between runs on the 2-core
// machine (docs/benchmarks.md).
inline constexpr int kRepetitions = 5;

struct Options {
    bool quick = false;       // tiny settings: checks the harness, measures nothing useful
    int reps = kRepetitions;  // interleaved repetitions (--repetitions)
    int max_threads = 0;      // scaling goes 1 .. this (0: all hardware threads)
    std::filesystem::path scenes;
    std::vector<std::string> only;  // engines, scaling, error_time: these bench scenes only
    std::vector<size_t> triangles;  // scene_size: these sizes only (default 10^4 .. 10^7)
    SamplerKind sampler = RenderRequest{}.sampler;  // engines, waves, scaling (--sampler)

    int repetitions() const { return quick ? 1 : reps; }

    bool wants(const std::string& scene) const {
        return only.empty() || std::find(only.begin(), only.end(), scene) != only.end();
    }
};

// One render of `request` by `engine` into a new film, on our BVH or on Embree; the film's
// mean goes to `mean` if given.
template <class Tracer>
RenderStats render_once(const Scene& scene,
                        const Tracer& tracer,
                        RenderRequest request,
                        Engine engine,
                        Image* mean = nullptr) {
    request.engine = engine;
    Film film(request.width, request.height);
    const RenderStats stats = render(scene, tracer, request, film);
    if (mean) *mean = film.mean();
    return stats;
}

void bench_engines(const Options& o, Results& r);      // megakernel vs wavefront, A B A B ...
void bench_waves(const Options& o, Results& r);        // wavefront speed vs wave size
void bench_bvh(const Options& o, Results& r);          // our BVH vs Embree on captured rays
void bench_scene_size(const Options& o, Results& r);   // the same, 10^4 to 10^7 triangles
void bench_scaling(const Options& o, Results& r);      // threads 1..N, both engines
void bench_convergence(const Options& o, Results& r);  // rMSE vs time per strategy
void bench_error_time(const Options& o, Results& r);   // rMSE vs time per engine and sampler
void bench_python_rays(const Options& o, Results& r);  // Bvh.intersect from NumPy vs C++

}  // namespace wavetrace::bench
