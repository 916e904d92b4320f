// Micro-benchmarks of the wavefront's kernels (Google Benchmark), on waves captured from real
// scenes: one wave of camera rays is generated and traced once, and each benchmark runs one
// stage over that captured state, restoring its inputs between iterations. Items per second
// are queue entries per second.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "kernels/kernels.h"
#include "wavetrace/wavetrace.h"

using namespace wavetrace;

namespace {

constexpr size_t kWave = 4096;  // the default wave: one thread's share of a pass

// A scene with everything a wave needs, and one wave captured after its first intersection.
struct Captured {
    Scene scene;
    Bvh bvh;
    std::unique_ptr<LightSet> lights;
    RenderConfig config;
    std::unique_ptr<CameraRays> camera;
    std::unique_ptr<WaveInputs> in;
    WaveQueues unsorted;  // after generate + intersect
    WaveQueues q;         // ... + sort_by_material
    KeyRanges ranges{};
    WaveQueues shaded;  // after shade + intersect_shadow
    size_t n = 0, shadows = 0;

    explicit Captured(const std::string& name) {
        scene = load_scene(std::string(WAVETRACE_SCENES_DIR) + "/" + name + ".json");
        bvh = Bvh::build(scene);
        lights = std::make_unique<LightSet>(scene);
        config.width = 64;  // 64 x 64 = one wave: the whole image, every material kind
        config.height = 64;
        config.spp = 1;
        config.seed = 1;
        camera = std::make_unique<CameraRays>(scene.camera, config.width, config.height);
        in = std::make_unique<WaveInputs>(WaveInputs{scene, *lights, config, *camera,
                                                     media_at(scene, bvh, scene.camera.look_from)});
        n = kWave;
        q.resize(n);
        generate(*in, 0, 0, 0, n, q.paths, q.rays);
        intersect(bvh, q.rays, 0, n, q.hits);
        unsorted = q;
        ranges = sort_by_material(scene, n, q.key, q.paths, q.rays, q.hits);
        shaded = q;
        shadows = shade(*in, 0, shaded.hits, 0, n, shaded.paths, shaded.rays, shaded.keep,
                        shaded.shadows, 0);
        intersect_shadow(bvh, *in, shaded.shadows, shaded.paths, 0, shadows, shaded.transmittance);
    }
};

Captured& scene(const std::string& name) {
    static std::map<std::string, std::unique_ptr<Captured>> cache;
    auto& c = cache[name];
    if (!c) c = std::make_unique<Captured>(name);
    return *c;
}

void BM_Generate(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.q;
    for (auto _ : st) generate(*c.in, 0, 0, 0, c.n, q.paths, q.rays);
    st.SetItemsProcessed(st.iterations() * c.n);
}

void BM_IntersectClosest(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.q;
    for (auto _ : st) intersect(c.bvh, q.rays, 0, c.n, q.hits);
    st.SetItemsProcessed(st.iterations() * c.n);
}

void BM_SortByMaterial(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.q;
    for (auto _ : st) {
        st.PauseTiming();
        q = c.unsorted;
        st.ResumeTiming();
        benchmark::DoNotOptimize(sort_by_material(c.scene, c.n, q.key, q.paths, q.rays, q.hits));
    }
    st.SetItemsProcessed(st.iterations() * c.n);
}

// Shading one sort key's range (light sampling included): contiguous after sort_by_material.
void BM_ShadeKind(benchmark::State& st, const char* name, int kind) {
    Captured& c = scene(name);
    const size_t begin = c.ranges[kind], end = c.ranges[kind + 1];
    if (begin >= end) {
        st.SkipWithError("no hits of this kind in the captured wave");
        return;
    }
    WaveQueues q = c.q;
    for (auto _ : st) {
        st.PauseTiming();
        q.paths = c.q.paths;  // shade consumes path state and rays: restore them
        q.rays = c.q.rays;
        st.ResumeTiming();
        benchmark::DoNotOptimize(
            shade(*c.in, 0, q.hits, begin, end, q.paths, q.rays, q.keep, q.shadows, 0));
    }
    st.SetItemsProcessed(st.iterations() * (end - begin));
}

void BM_IntersectShadow(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st)
        benchmark::DoNotOptimize(
            intersect_shadow(c.bvh, *c.in, q.shadows, q.paths, 0, c.shadows, q.transmittance));
    st.SetItemsProcessed(st.iterations() * c.shadows);
}

void BM_MisCombine(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st) mis_combine(q.shadows, q.transmittance, 0, c.shadows, q.paths);
    st.SetItemsProcessed(st.iterations() * c.shadows);
}

void BM_Compact(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st) {
        st.PauseTiming();
        q.paths = c.shaded.paths;
        q.rays = c.shaded.rays;
        st.ResumeTiming();
        benchmark::DoNotOptimize(compact(q.keep, c.n, q.paths, q.rays));
    }
    st.SetItemsProcessed(st.iterations() * c.n);
}

}  // namespace

#define WAVETRACE_KERNEL_BENCH(fn, scene_name) \
    BENCHMARK_CAPTURE(fn, scene_name, #scene_name)->Unit(benchmark::kMicrosecond)->UseRealTime()

WAVETRACE_KERNEL_BENCH(BM_Generate, cornell);
WAVETRACE_KERNEL_BENCH(BM_IntersectClosest, cornell);
WAVETRACE_KERNEL_BENCH(BM_IntersectClosest, dragon);
WAVETRACE_KERNEL_BENCH(BM_IntersectClosest, everything);
WAVETRACE_KERNEL_BENCH(BM_SortByMaterial, cornell);
WAVETRACE_KERNEL_BENCH(BM_SortByMaterial, everything);
BENCHMARK_CAPTURE(BM_ShadeKind, cornell_lambertian, "cornell", 1 + int(MaterialKind::Lambertian))
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ShadeKind, dragon_metal, "dragon", 1 + int(MaterialKind::Metal))
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ShadeKind,
                  everything_dielectric,
                  "everything",
                  1 + int(MaterialKind::Dielectric))
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ShadeKind, cornell_miss, "cornell", 0)
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ShadeKind,
                  cornell_smoke_interface,
                  "cornell-smoke",
                  1 + int(MaterialKind::Interface))
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_ShadeKind, cornell_light, "cornell", 1 + int(MaterialKind::DiffuseLight))
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
WAVETRACE_KERNEL_BENCH(BM_IntersectShadow, cornell);
WAVETRACE_KERNEL_BENCH(BM_IntersectShadow, dragon);
WAVETRACE_KERNEL_BENCH(BM_MisCombine, cornell);
WAVETRACE_KERNEL_BENCH(BM_Compact, cornell);

BENCHMARK_MAIN();
