// wavetrace_bench: the benchmark suite. Runs each section side by side in this one process and
// writes results/ (JSON, one CSV per table). `--quick` runs tiny settings, for the test suite.
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>

#include "sections.h"
#include "wavetrace/engines/render.h"

int main(int argc, char** argv) {
    using namespace wavetrace::bench;
    CLI::App app{"wavetrace benchmark suite"};
    Options o;
    std::string out = "results", scenes = WAVETRACE_SCENES_DIR;
    std::vector<std::string> sections = {"engines", "waves",       "bvh",        "scene_size",
                                         "scaling", "convergence", "error_time", "python_rays"};
    app.add_flag("--quick", o.quick, "tiny settings: check the harness only");
    app.add_option("--out", out, "results folder")->capture_default_str();
    app.add_option("--scenes", scenes, "scenes folder")->capture_default_str();
    app.add_option("--sections", sections, "sections to run")
        ->check(CLI::IsMember({"engines", "waves", "bvh", "scene_size", "scaling", "convergence",
                               "error_time", "python_rays"}));
    app.add_option("--max-threads", o.max_threads,
                   "scaling: up to this many threads (default: all)");
    app.add_option("--repetitions", o.reps,
                   "engines, bvh, scaling: interleaved repetitions to take medians of")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_option("--scene", o.only,
                   "engines, scaling, error_time: only these bench scenes (repeatable)")
        ->check(CLI::IsMember({"cornell", "everything", "bunny", "dragon", "veach-mis", "materials",
                               "dragon-envmap", "cornell-glass", "cornell-mirror", "cornell-smoke",
                               "cornell-mcguire"}));
    app.add_option("--triangles", o.triangles,
                   "scene_size: only the scenes grown to these triangle counts (repeatable)")
        ->check(CLI::Range(size_t(1'000), size_t(100'000'000)));
    std::string sampler;
    app.add_option("--sampler", sampler,
                   "engines, waves, scaling: the sampler the renders draw from (default: the "
                   "library's)")
        ->check(CLI::IsMember({"independent", "sobol", "zsobol"}));
    std::string simd;
    app.add_option("--simd", simd,
                   "run every kernel on this SIMD target (e.g. AVX2; default: the best this CPU "
                   "runs)");
    CLI11_PARSE(app, argc, argv);
    o.scenes = scenes;
    if (!sampler.empty()) o.sampler = *wavetrace::parse_sampler(sampler);
    if (!wavetrace::use_simd_target(simd)) {
        std::string names;
        for (const std::string& t : wavetrace::simd_targets()) names += " " + t;
        std::cerr << "--simd " << simd << ": not a target this CPU runs (it runs:" << names
                  << ")\n";
        return 2;
    }

    Results r;
    std::string cpu = "unknown";
    {
        std::ifstream info("/proc/cpuinfo");
        for (std::string line; std::getline(info, line);)
            if (line.rfind("model name", 0) == 0) {
                cpu = line.substr(line.find(':') + 2);
                break;
            }
    }
    r.note("cpu", cpu);
    r.note("hardware_threads", tbb::this_task_arena::max_concurrency());
    r.note("quick", o.quick);
    r.note("simd", wavetrace::simd_target());
    r.note("sampler", wavetrace::to_string(o.sampler));
    r.note("wavefront_bytes_per_path", wavetrace::wavefront_bytes_per_path());
    auto start = std::chrono::steady_clock::now();
    for (const std::string& s : sections) {
        if (s == "engines") bench_engines(o, r);
        if (s == "waves") bench_waves(o, r);
        if (s == "bvh") bench_bvh(o, r);
        if (s == "scene_size") bench_scene_size(o, r);
        if (s == "scaling") bench_scaling(o, r);
        if (s == "convergence") bench_convergence(o, r);
        if (s == "error_time") bench_error_time(o, r);
        if (s == "python_rays") bench_python_rays(o, r);
    }
    r.note("seconds",
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    r.save(out);
    std::printf("results written to %s/\n", out.c_str());
    return 0;
}
