// Micro-benchmarks of the wavefront's kernels (Google Benchmark), on waves captured from real
// scenes: one wave of camera rays is generated and traced once, and each benchmark runs one
// stage over that captured state, restoring its inputs between iterations. Items per second
// are queue entries per second.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "kernels/kernels.h"
#include "queues/compact.h"
#include "wavetrace/wavetrace.h"

using namespace wavetrace;

namespace {

constexpr size_t kWave = 1 << 16;

// A scene with everything a wave needs, and the wave captured after its first intersection.
struct Captured {
    Scene scene;
    Bvh bvh;
    std::unique_ptr<LightSet> lights;
    RenderConfig config;
    std::unique_ptr<CameraRays> camera;
    std::unique_ptr<WaveInputs> in;
    WaveQueues q;       // after generate + intersect + bucket
    WaveQueues shaded;  // after shade + light_sample + shadow compaction + intersect_shadow
    size_t n = 0, shadows = 0;

    explicit Captured(const std::string& name) {
        scene = load_scene(std::string(WAVETRACE_SCENES_DIR) + "/" + name + ".json");
        bvh = Bvh::build(scene);
        lights = std::make_unique<LightSet>(scene);
        config.width = 256;
        config.height = 256;
        config.spp = 1;
        config.seed = 1;
        camera = std::make_unique<CameraRays>(scene.camera, config.width, config.height);
        in = std::make_unique<WaveInputs>(WaveInputs{scene, *lights, config, *camera,
                                                     media_at(scene, bvh, scene.camera.look_from)});
        n = kWave;
        q.resize(n);
        generate(*in, q, 0, 0, n);
        intersect(bvh, q, 0, n);
        bucket_by_material(*in, q, n);
        shaded = q;
        shade(*in, shaded, 0, n);
        light_sample(*in, shaded, 0, n);
        shadows = stable_compact(std::span(shaded.shadow_keep.data(), n), shaded.compacted);
        for (size_t k = 0; k < shadows; ++k)
            shaded.shadow.copy_from(k, shaded.shadow_candidates, shaded.compacted[k]);
        intersect_shadow(bvh, *in, shaded, 0, shadows);
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
    for (auto _ : st) generate(*c.in, q, 0, 0, c.n);
    st.SetItemsProcessed(st.iterations() * c.n);
}

void BM_IntersectClosest(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.q;
    for (auto _ : st) intersect(c.bvh, q, 0, c.n);
    st.SetItemsProcessed(st.iterations() * c.n);
}

void BM_BucketByMaterial(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.q;
    for (auto _ : st) bucket_by_material(*c.in, q, c.n);
    st.SetItemsProcessed(st.iterations() * c.n);
}

// Shading one material kind's bucket: the contiguous range of `order` whose hits have it.
void BM_ShadeKind(benchmark::State& st, const char* name, int kind) {
    Captured& c = scene(name);
    size_t begin = c.n, end = 0;
    for (size_t k = 0; k < c.n; ++k) {
        PrimRef prim = c.q.hits.prim[c.q.order[k]];
        int key = prim.valid() ? 1 + int(c.scene.materials[c.scene.prim_material(prim)].kind) : 0;
        if (key == kind) {
            begin = std::min(begin, k);
            end = k + 1;
        }
    }
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
        shade(*c.in, q, begin, end);
    }
    st.SetItemsProcessed(st.iterations() * (end - begin));
}

void BM_LightSample(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st) light_sample(*c.in, q, 0, c.n);
    st.SetItemsProcessed(st.iterations() * c.n);
}

void BM_IntersectShadow(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st) benchmark::DoNotOptimize(intersect_shadow(c.bvh, *c.in, q, 0, c.shadows));
    st.SetItemsProcessed(st.iterations() * c.shadows);
}

void BM_MisCombine(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st) mis_combine(*c.in, q, 0, c.shadows);
    st.SetItemsProcessed(st.iterations() * c.shadows);
}

void BM_CompactRays(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st) {
        size_t n = stable_compact(std::span(q.keep.data(), c.n), q.compacted);
        for (size_t k = 0; k < n; ++k) q.next_rays.copy_from(k, q.rays, q.compacted[k]);
        benchmark::DoNotOptimize(n);
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
WAVETRACE_KERNEL_BENCH(BM_BucketByMaterial, everything);
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
WAVETRACE_KERNEL_BENCH(BM_LightSample, cornell);
WAVETRACE_KERNEL_BENCH(BM_LightSample, dragon);
WAVETRACE_KERNEL_BENCH(BM_IntersectShadow, cornell);
WAVETRACE_KERNEL_BENCH(BM_IntersectShadow, dragon);
WAVETRACE_KERNEL_BENCH(BM_MisCombine, cornell);
WAVETRACE_KERNEL_BENCH(BM_CompactRays, cornell);

BENCHMARK_MAIN();
