// Micro-benchmarks of the wavefront's kernels (Google Benchmark), on waves captured from real
// scenes: one wave of camera rays is generated and traced once, and each benchmark runs one
// stage over that captured state, restoring its inputs between iterations. Items per second
// are queue entries per second. The lane kernels (blocks/lane_kernels.h) are measured against
// their one-lane instances, what the megakernel runs, on the same rows: what SIMD buys per
// formula.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "blocks/lane_kernels.h"
#include "kernels/kernels.h"
#include "shading/lane_routes.h"
#include "shading/path_vertex.h"
#include "wavetrace/wavetrace.h"

using namespace wavetrace;

namespace {

constexpr size_t kWave = 4096;  // the default wave: one thread's share of a pass

// A scene with everything a wave needs, and one wave captured after its first intersection.
struct Captured {
    Scene scene;
    Bvh bvh;
    std::unique_ptr<LightSet> lights;
    RenderRequest config;
    std::unique_ptr<CameraRays> camera;
    std::unique_ptr<WaveInputs> in;
    WaveQueues unsorted;  // after generate + intersect
    WaveQueues q;         // ... + sort_by_material
    KeyRanges ranges{};
    WaveQueues shaded;  // after shade + light_sample + intersect_shadow
    size_t n = 0, shadows = 0;
    ShadeCounts found;

    explicit Captured(const std::string& name) {
        scene = load_scene(std::string(WAVETRACE_SCENES_DIR) + "/" + name + ".json");
        bvh = Bvh::build(scene);
        lights = std::make_unique<LightSet>(scene);
        config.width = 64;  // 64 x 64 = one wave: the whole image, every material kind
        config.height = 64;
        config.spp = 1;
        config.seed = 1;
        camera = std::make_unique<CameraRays>(scene.camera, config.width, config.height);
        in = std::make_unique<WaveInputs>(WaveInputs{scene, *lights, config.estimator, Sampler{config.seed},
                                                     config.width, config.height, *camera,
                                                     media_at(scene, bvh, scene.camera.look_from),
                                                     shadows_walk(scene)});
        n = kWave;
        q.resize(n);
        generate(*in, WaveSamples{}, 0, 0, n, q.paths, q.rays);
        intersect(bvh, q.rays, 0, n, q.hits);
        unsorted = q;
        ranges = sort_by_material(scene, 0, n, q.key, q.paths, q.rays, q.hits);
        shaded = q;
        found = shade(*in, shaded.hits, 0, n, shaded.paths, shaded.rays, shaded.keep,
                      shaded.light_samples, 0, shaded.emissions, 0);
        shadows = light_sample(*in, shaded.light_samples, 0, found.light_samples, shaded.shadows, 0,
                               shaded.paths);
        intersect_shadow(bvh, *in, shaded.shadows, 0, shadows, shaded.transmittance);
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
    for (auto _ : st) generate(*c.in, WaveSamples{}, 0, 0, c.n, q.paths, q.rays);
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
        benchmark::DoNotOptimize(sort_by_material(c.scene, 0, c.n, q.key, q.paths, q.rays, q.hits));
    }
    st.SetItemsProcessed(st.iterations() * c.n);
}

// Shading one sort key's range: contiguous after sort_by_material.
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
        benchmark::DoNotOptimize(shade(*c.in, q.hits, begin, end, q.paths, q.rays, q.keep,
                                       q.light_samples, 0, q.emissions, 0));
    }
    st.SetItemsProcessed(st.iterations() * (end - begin));
}

void BM_LightSample(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st)
        benchmark::DoNotOptimize(
            light_sample(*c.in, q.light_samples, 0, c.found.light_samples, q.shadows, 0, q.paths));
    st.SetItemsProcessed(st.iterations() * c.found.light_samples);
}

void BM_IntersectShadow(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st)
        benchmark::DoNotOptimize(
            intersect_shadow(c.bvh, *c.in, q.shadows, 0, c.shadows, q.transmittance));
    st.SetItemsProcessed(st.iterations() * c.shadows);
}

void BM_MisCombine(benchmark::State& st, const char* name) {
    Captured& c = scene(name);
    WaveQueues q = c.shaded;
    for (auto _ : st)
        mis_combine(c.config.estimator, mis_heuristics(c.config.estimator, *c.lights), q.emissions,
                    {0, c.found.emissions}, q.shadows, q.transmittance, {0, c.shadows}, q.paths);
    st.SetItemsProcessed(st.iterations() * (c.shadows + c.found.emissions));
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

// Up to kShadeChunk Lambertian scattering vertices of the captured cornell wave, as shade
// finds them, with their samples and the light each light sample picks.
struct LambertianRows {
    Captured& c;
    std::vector<Vertex> v;
    std::vector<Vec3> wo;
    std::vector<Color> beta;
    std::vector<VertexSamples> u;
    std::vector<uint32_t> pixel;
    std::vector<uint16_t> bounce;
    std::vector<float> x, y;

    LambertianRows() : c(scene("cornell")) {
        for (size_t i = 0; i < c.n && v.size() < kShadeChunk; ++i) {
            MediumStack media;
            float flight = 0;
            const SegmentResult seg = resolve_segment(
                c.scene, *c.lights, c.config.estimator, ray_at(c.unsorted.rays, i),
                hit_at(c.unsorted.hits, i), media, flight, previous_vertex(c.unsorted.paths, i));
            if (seg.event != SegmentEvent::Scatter ||
                !takes_lane_step(c.config.estimator, seg.vertex, *c.lights))
                continue;
            const uint32_t p = c.unsorted.paths.pixel[i];
            v.push_back(seg.vertex);
            wo.push_back(seg.wo);
            beta.push_back(Color(0.8f));
            u.push_back(vertex_samples(Sampler{c.config.seed}, p, 0, 1, true));
            pixel.push_back(p);
            bounce.push_back(1);
            x.push_back(float(p % uint32_t(c.config.width)));
            y.push_back(float(p / uint32_t(c.config.width)));
        }
    }
};

LambertianRows& lambertian_rows() {
    static LambertianRows rows;
    return rows;
}

// The sampler of a 320 x 320 render of 16 samples per pixel (the engines bench's).
Sampler bench_sampler(SamplerKind kind) {
    return kind == SamplerKind::ZSobol ? zsobol_sampler(1, 320, 320, 16) : Sampler{1, kind};
}

void BM_CameraRays(benchmark::State& st, bool lanes, SamplerKind kind) {
    LambertianRows& r = lambertian_rows();
    const size_t n = r.v.size();
    const Sampler sampler = bench_sampler(kind);
    const std::vector<uint32_t> sample(n, 0);
    CameraRayBlock block;
    for (auto _ : st) {
        if (lanes) {
            draw_camera_rays(*r.c.camera, sampler, sample.data(), r.pixel.data(), r.x.data(),
                             r.y.data(), n, false, block);
            benchmark::DoNotOptimize(block);
        } else {
            for (size_t k = 0; k < n; ++k)
                benchmark::DoNotOptimize(generate_camera_ray(*r.c.camera, sampler, r.pixel[k], 0,
                                                             int(r.x[k]), int(r.y[k])));
        }
    }
    st.SetItemsProcessed(st.iterations() * n);
}

void BM_VertexSamples(benchmark::State& st, bool lanes, SamplerKind kind) {
    LambertianRows& r = lambertian_rows();
    const size_t n = r.v.size();
    const Sampler sampler = bench_sampler(kind);
    const std::vector<uint32_t> sample(n, 0);
    SampleBlock block;
    for (auto _ : st) {
        if (lanes) {
            draw_vertex_samples(sampler, sample.data(), r.pixel.data(), r.bounce.data(), n, true,
                                false, block);
            benchmark::DoNotOptimize(block);
        } else {
            for (size_t k = 0; k < n; ++k)
                benchmark::DoNotOptimize(vertex_samples(sampler, r.pixel[k], 0, r.bounce[k], true));
        }
    }
    st.SetItemsProcessed(st.iterations() * n);
}

// The continuation at Lambertian vertices. One lane: continue_path per vertex. Lanes: gathering
// the rows (push), then the vector kernel.
void fill(LambertianRows& r, VertexBlock& block) {
    block.n = 0;
    for (size_t k = 0; k < r.v.size(); ++k) {
        const size_t row = block.push(k, r.v[k], r.wo[k], r.beta[k]);
        block.set_step(row, r.u[k].continuation, r.u[k].roulette, true);
    }
}

void BM_LambertianSteps(benchmark::State& st, bool lanes) {
    LambertianRows& r = lambertian_rows();
    const size_t n = r.v.size();
    VertexBlock block;
    for (auto _ : st) {
        if (lanes) {
            fill(r, block);
            step_vertices(block);
            benchmark::DoNotOptimize(block);
        } else {
            for (size_t k = 0; k < n; ++k) {
                MediumStack media;
                benchmark::DoNotOptimize(continue_path(r.c.scene, *r.c.lights, r.c.config.estimator,
                                                       r.v[k], r.wo[k], PreviousVertex{}, 4,
                                                       r.beta[k], 1.0f, media,
                                                       r.u[k].continuation, r.u[k].roulette));
            }
        }
    }
    st.SetItemsProcessed(st.iterations() * n);
}

// The light samples of the same vertices towards the quad light. One lane: next_event per
// vertex. Lanes: queueing the rows, then the vector kernel.
void fill(LambertianRows& r, LightSampleQueue& queue, LightSampleBlock& block) {
    queue.resize(r.v.size());
    block.queue = &queue;
    block.first = 0;
    block.n = r.v.size();
    for (size_t k = 0; k < r.v.size(); ++k) {
        const Vertex& v = r.v[k];
        store_queued_vertex(queue, k, {uint32_t(k),
                                       v.p,
                                       v.ng,
                                       v.frame.n,
                                       v.frame_angle,
                                       v.unbent,
                                       v.bump_alpha2,
                                       r.wo[k],
                                       v.bsdf.albedo,
                                       v.bsdf.alpha,
                                       v.bsdf.alpha_v,
                                       v.bsdf.metallic,
                                       v.bsdf.coat_normal,
                                       v.uv,
                                       v.bsdf.kind,
                                       kNone,
                                       r.beta[k],
                                       r.u[k].light_select,
                                       r.u[k].light_u,
                                       r.u[k].light_v});
        const LightChoice light = r.c.lights->select(r.u[k].light_select, v.p, v.ng);
        block.lobe[k] = int32_t(LaneLobe::Lambertian);
        block.planar[k] = r.c.lights->planar_emitter_index(light);
        block.sphere[k] = -1;
        block.delta[k] = -1;
        block.environment[k] = 0;
        block.select_prob[k] = light.probability;
    }
}

void BM_LambertianLightSamples(benchmark::State& st, bool lanes) {
    LambertianRows& r = lambertian_rows();
    const size_t n = r.v.size();
    LightSampleQueue queue;
    LightSampleBlock block;
    ShadowQueue shadows;
    shadows.resize(n);
    for (auto _ : st) {
        if (lanes) {
            fill(r, queue, block);
            benchmark::DoNotOptimize(sample_lights_in_lanes(block, *r.c.lights, shadows, 0));
        } else {
            for (size_t k = 0; k < n; ++k)
                benchmark::DoNotOptimize(next_event(r.c.scene, *r.c.lights, r.c.config.estimator,
                                                    r.v[k], r.wo[k], r.u[k]));
        }
    }
    st.SetItemsProcessed(st.iterations() * n);
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
WAVETRACE_KERNEL_BENCH(BM_LightSample, cornell);
BENCHMARK_CAPTURE(BM_LightSample, veach_mis, "veach-mis")
    ->Unit(benchmark::kMicrosecond)
    ->UseRealTime();
WAVETRACE_KERNEL_BENCH(BM_IntersectShadow, cornell);
WAVETRACE_KERNEL_BENCH(BM_IntersectShadow, dragon);
WAVETRACE_KERNEL_BENCH(BM_MisCombine, cornell);
WAVETRACE_KERNEL_BENCH(BM_Compact, cornell);

// One lane (the megakernel's instance) against the vector kernel, on the same rows; the
// vector kernels of the blocks include gathering the rows (push), as shade does.
#define WAVETRACE_LANES_BENCH(fn)                                                         \
    BENCHMARK_CAPTURE(fn, one_lane, false)->Unit(benchmark::kMicrosecond)->UseRealTime(); \
    BENCHMARK_CAPTURE(fn, lanes, true)->Unit(benchmark::kMicrosecond)->UseRealTime()
// The same for each sampler.
#define WAVETRACE_SAMPLER_BENCH(fn)                                    \
    BENCHMARK_CAPTURE(fn, one_lane, false, SamplerKind::Independent)   \
        ->Unit(benchmark::kMicrosecond)                                \
        ->UseRealTime();                                               \
    BENCHMARK_CAPTURE(fn, lanes, true, SamplerKind::Independent)       \
        ->Unit(benchmark::kMicrosecond)                                \
        ->UseRealTime();                                               \
    BENCHMARK_CAPTURE(fn, one_lane_sobol, false, SamplerKind::Sobol)   \
        ->Unit(benchmark::kMicrosecond)                                \
        ->UseRealTime();                                               \
    BENCHMARK_CAPTURE(fn, lanes_sobol, true, SamplerKind::Sobol)       \
        ->Unit(benchmark::kMicrosecond)                                \
        ->UseRealTime();                                               \
    BENCHMARK_CAPTURE(fn, one_lane_zsobol, false, SamplerKind::ZSobol) \
        ->Unit(benchmark::kMicrosecond)                                \
        ->UseRealTime();                                               \
    BENCHMARK_CAPTURE(fn, lanes_zsobol, true, SamplerKind::ZSobol)     \
        ->Unit(benchmark::kMicrosecond)                                \
        ->UseRealTime()
WAVETRACE_SAMPLER_BENCH(BM_CameraRays);
WAVETRACE_SAMPLER_BENCH(BM_VertexSamples);
WAVETRACE_LANES_BENCH(BM_LambertianSteps);
WAVETRACE_LANES_BENCH(BM_LambertianLightSamples);

BENCHMARK_MAIN();
