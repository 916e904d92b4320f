// Each wavefront kernel alone, on small hand-made queues in a small hand-made scene: a floor
// under a square light, a metal ball, and a blocker below the floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "engines/wavefront.h"
#include "kernels/kernels.h"
#include "sampling/sampler.h"
#include "shading/mis.h"
#include "shading/path_vertex.h"
#include "wavetrace/accel/bvh.h"

using namespace wavetrace;

namespace {

struct World {
    Scene scene;
    Bvh bvh;
    RenderRequest config;
    std::unique_ptr<LightSet> lights;
    std::unique_ptr<CameraRays> camera;
    std::unique_ptr<WaveInputs> in;
    WaveQueues q;

    World() {
        Material floor;
        floor.albedo = scene.add_solid({0.5f, 0.6f, 0.7f});
        Material light;
        light.kind = MaterialKind::DiffuseLight;
        light.emission = scene.add_solid({4, 3, 2});
        Material metal;
        metal.kind = MaterialKind::Metal;
        metal.albedo = scene.add_solid(Color(0.9f));
        metal.roughness = 0.3f;
        const MaterialId f = scene.add_material(floor), l = scene.add_material(light),
                         m = scene.add_material(metal);
        scene.add_quad({{-1, 0, 1}, {2, 0, 0}, {0, 0, -2}, f, kNone});                // normal +y
        scene.add_quad({{-0.25f, 1, -0.25f}, {0.5f, 0, 0}, {0, 0, 0.5f}, l, kNone});  // faces -y
        scene.add_sphere({{3, 0.5f, 0}, 0.5f, m, kNone});
        scene.add_quad({{-1, -1, 1}, {2, 0, 0}, {0, 0, -2}, f, kNone});  // under the floor
        scene.camera.look_from = {0, 0.5f, 3};
        scene.camera.look_at = {0, 0.5f, 0};
        bvh = Bvh::build(scene);
        config.width = 4;
        config.height = 3;
        config.seed = 7;
        config.estimator.max_depth = 5;
        config.estimator.strategy = Strategy::Nee;
        lights = std::make_unique<LightSet>(scene);
        camera = std::make_unique<CameraRays>(scene.camera, config.width, config.height);
        in = std::make_unique<WaveInputs>(WaveInputs{scene, *lights, config.estimator, Sampler{config.seed},
                                                     config.width, config.height, *camera,
                                                     MediumStack{}, shadows_walk(scene)});
        q.resize(16);
    }

    // Entry i: a fresh path (pixel 10 + i) whose ray is `ray`, traced into the hit queue.
    // Path i of pixel 10 + i, sample `sample`, on `ray`, with its hit.
    void start(size_t i, Ray ray, uint32_t sample = 0) {
        q.paths.store(i, PathQueue::Entry{.pixel = static_cast<uint32_t>(10 + i),
                                          .sample = sample,
                                          .slot = static_cast<uint32_t>(i),
                                          .bounce = 0,
                                          .crossings = 0,
                                          .counts_fully = 1,
                                          .beta = Color(1.0f),
                                          .radiance = Color(0.0f),
                                          .prev_p = ray.o,
                                          .prev_pdf = 0.0f,
                                          .media = {},
                                          .flight = 0.0f});
        set_ray(q.rays, i, ray);
        intersect(bvh, q.rays, i, i + 1, q.hits);
    }
};

}  // namespace

TEST(Kernels, PassOrderVisitsEveryPixelOnceInTiles) {
    for (auto [w, h] : {std::pair{4u, 3u}, {1u, 1u}, {7u, 5u}, {320u, 240u}, {9u, 1u}, {1u, 9u}}) {
        std::vector<int> seen(w * h, 0);
        for (uint32_t k = 0; k < w * h; ++k) {
            const uint32_t p = pixel_in_pass_order(k, w, h);
            ASSERT_LT(p, w * h);
            ++seen[p];
        }
        EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), int(w * h)) << w << "x" << h;
        // The walk gives the same pixels from any start.
        for (uint32_t start : {0u, 1u, 5u, w * h / 2, w * h - 1}) {
            if (start >= w * h) continue;
            PassOrderWalk walk(start, w, h);
            for (uint32_t k = start; k < w * h; ++k, walk.next())
                ASSERT_EQ(walk.y() * w + walk.x(), pixel_in_pass_order(k, w, h))
                    << w << "x" << h << " from " << start << " at " << k;
        }
    }
    // A full 4x2 tile first: (0,0) (1,0) (2,0) (3,0) (0,1) (1,1) (2,1) (3,1), then the next.
    const uint32_t first[] = {0, 1, 2, 3, 10, 11, 12, 13, 4, 5};
    for (uint32_t k = 0; k < std::size(first); ++k)
        EXPECT_EQ(pixel_in_pass_order(k, 10, 6), first[k]) << k;
}

TEST(Kernels, GenerateStartsPathsAtTheirPixelsWithCameraRays) {
    World w;
    generate(*w.in, WaveSamples{5, 1}, 2, 0, 6, w.q.paths, w.q.rays);
    for (uint32_t i = 0; i < 6; ++i) {
        const uint32_t pixel = pixel_in_pass_order(2 + i, 4, 3);
        EXPECT_EQ(w.q.paths.pixel[i], pixel);
        EXPECT_EQ(w.q.paths.sample[i], 5u);
        EXPECT_EQ(w.q.paths.slot[i], i);
        EXPECT_EQ(w.q.paths.bounce[i], 0);
        EXPECT_EQ(w.q.paths.counts_fully[i], 1);
        EXPECT_EQ(w.q.paths.beta[i], Color(1.0f));
        EXPECT_EQ(w.q.paths.radiance[i], Color(0.0f));
        const Ray expect =
            generate_camera_ray(*w.camera, Sampler{w.config.seed}, pixel, 5, static_cast<int>(pixel % 4),
                                static_cast<int>(pixel / 4));
        EXPECT_EQ(w.q.rays.origin[i], expect.o);
        EXPECT_EQ(w.q.rays.dir[i], expect.d);
        EXPECT_EQ(w.q.paths.prev_p[i], expect.o);
    }
}

// Several samples of each pixel side by side: entries [4, 11) of a wave of the pixels visited
// from the second on, samples 7, 8 and 9 of each: each its pixel's, sample's and slot's, with
// the megakernel's camera ray of that sample.
TEST(Kernels, GenerateCarriesSeveralSamplesOfAPixel) {
    World w;
    generate(*w.in, WaveSamples{7, 3}, 1, 4, 11, w.q.paths, w.q.rays);
    for (uint32_t i = 4; i < 11; ++i) {
        const uint32_t pixel = pixel_in_pass_order(1 + i / 3, 4, 3), sample = 7 + i % 3;
        EXPECT_EQ(w.q.paths.pixel[i], pixel) << i;
        EXPECT_EQ(w.q.paths.sample[i], sample) << i;
        EXPECT_EQ(w.q.paths.slot[i], i);
        const Ray expect =
            generate_camera_ray(*w.camera, Sampler{w.config.seed}, pixel, sample,
                                static_cast<int>(pixel % 4), static_cast<int>(pixel / 4));
        EXPECT_EQ(w.q.rays.origin[i], expect.o) << i;
        EXPECT_EQ(w.q.rays.dir[i], expect.d) << i;
    }
}

TEST(Kernels, SortByMaterialMakesKindsContiguousAndMovesWholeEntries) {
    World w;
    const Point3 above{0, 0.5f, 0};
    // miss, floor, light, metal ball, floor, miss, light, floor
    const Vec3 dirs[] = {{1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {1, 0, 0}};
    const int pattern[] = {0, 1, 2, 3, 1, 0, 2, 1};
    const size_t n = std::size(pattern);
    for (size_t i = 0; i < n; ++i) {
        // The ball is along +x from a point beside it; misses go along +x from above it.
        const Point3 o = pattern[i] == 3   ? Point3{1.5f, 0.5f, 0}
                         : pattern[i] == 0 ? Point3{0, 3, 0}
                                           : above;
        w.start(i, Ray{o, dirs[pattern[i]]});
        w.q.hits.u[i] = static_cast<float>(i);  // tags, to see that entries move whole
        w.q.rays.origin[i].z = static_cast<float>(i);
    }
    std::vector<PrimRef> prim_before(w.q.hits.prim.begin(), w.q.hits.prim.begin() + n);
    const KeyRanges ranges =
        sort_by_material(w.scene, 0, n, w.q.key, w.q.paths, w.q.rays, w.q.hits);

    EXPECT_EQ(ranges[kSortKeys], n);
    std::vector<int> tags;
    for (size_t i = 0; i < n; ++i) {
        const int key = sort_key(w.scene, w.q.hits.prim[i]);
        EXPECT_GE(i, ranges[key]) << i;
        EXPECT_LT(i, ranges[key + 1]) << i;
        if (i > 0) {
            EXPECT_LE(sort_key(w.scene, w.q.hits.prim[i - 1]), key);
        }
        const int tag = static_cast<int>(w.q.hits.u[i]);
        EXPECT_EQ(w.q.paths.pixel[i], 10u + tag);
        EXPECT_EQ(w.q.rays.origin[i].z, float(tag));
        EXPECT_EQ(w.q.hits.prim[i], prim_before[tag]);
        tags.push_back(tag);
    }
    std::sort(tags.begin(), tags.end());
    for (size_t i = 0; i < n; ++i) EXPECT_EQ(tags[i], int(i));
    EXPECT_EQ(ranges[1] - ranges[0], 2u);  // the two misses
    EXPECT_EQ(
        ranges[1 + int(MaterialKind::Lambertian) + 1] - ranges[1 + int(MaterialKind::Lambertian)],
        3u);
}

TEST(Kernels, ShadeQueuesALightSampleAndTheEmissionFoundAndContinues) {
    World w;
    const Point3 o{0.1f, 0.5f, 0.05f};
    const uint32_t sample = 3;
    w.start(0, Ray{o, {0, -1, 0}}, sample);         // the floor below the light
    w.start(1, Ray{o, {0, 1, 0}}, sample);          // the light's front
    w.start(2, Ray{{0, 3, 0}, {1, 0, 0}}, sample);  // nothing: a black background
    const ShadeCounts found = shade(*w.in, w.q.hits, 0, 3, w.q.paths, w.q.rays, w.q.keep,
                                    w.q.light_samples, 0, w.q.emissions, 0);

    // The floor: one light sample queued, the vertex as the megakernel resolves it.
    ASSERT_EQ(found.light_samples, 1u);
    const SurfaceHit s = surface_at(w.scene, Ray{o, {0, -1, 0}}, hit_at(w.q.hits, 0));
    const Vertex v = surface_vertex(w.scene, s, {0, 1, 0});
    const VertexSamples u = vertex_samples(Sampler{w.config.seed}, 10, sample, 0, true);
    const LightSampleQueue& ls = w.q.light_samples;
    EXPECT_EQ(ls.path[0], 0u);
    EXPECT_EQ(WAVETRACE_XYZ_AT(ls, p, 0), v.p);
    EXPECT_EQ(WAVETRACE_XYZ_AT(ls, ng, 0), v.ng);
    EXPECT_EQ(WAVETRACE_XYZ_AT(ls, ns, 0), v.frame.n);
    EXPECT_EQ(WAVETRACE_XYZ_AT(ls, wo, 0), (Vec3{0, 1, 0}));
    EXPECT_EQ(WAVETRACE_XYZ_AT(ls, albedo, 0), v.bsdf.albedo);
    EXPECT_EQ(ls.kind[0], MaterialKind::Lambertian);
    EXPECT_EQ(WAVETRACE_XYZ_AT(ls, beta, 0), Color(1.0f));
    EXPECT_EQ(ls.u_select[0], u.light_select);
    EXPECT_EQ(ls.u1[0], u.light_u);
    EXPECT_EQ(ls.u2[0], u.light_v);
    // ... and it goes on upwards from the floor (no roulette before rr_depth).
    EXPECT_EQ(w.q.keep[0], 1);
    EXPECT_EQ(w.q.paths.bounce[0], 1);
    EXPECT_GT(w.q.rays.dir[0].y, 0.0f);
    EXPECT_NEAR(w.q.rays.origin[0].y, 0.0f, 1e-4f);
    EXPECT_EQ(w.q.paths.counts_fully[0], 0);  // a Lambertian vertex samples lights
    EXPECT_EQ(w.q.paths.radiance[0], Color(0.0f));

    // The light seen by a camera-like ray: its emission queued, unweighted, and the path ends.
    ASSERT_EQ(found.emissions, 1u);
    EXPECT_EQ(w.q.emissions.path[0], 1u);
    EXPECT_EQ(w.q.emissions.radiance[0], Color(4, 3, 2));
    EXPECT_EQ(w.q.emissions.flags[0], kCountsFully);
    EXPECT_EQ(w.q.keep[1], 0);
    EXPECT_EQ(w.q.paths.radiance[1], Color(0.0f));  // mis_combine adds it
    // The background is black: nothing, and the path ends.
    EXPECT_EQ(w.q.keep[2], 0);
    EXPECT_EQ(w.q.paths.radiance[2], Color(0.0f));
}

// The light sample of a queued vertex: exactly the megakernel's (next_event), unweighted.
TEST(Kernels, LightSampleAppendsTheMegakernelsShadowRay) {
    World w;
    const Point3 o{0.1f, 0.5f, 0.05f};
    const uint32_t sample = 3;
    w.start(0, Ray{o, {0, -1, 0}}, sample);
    const ShadeCounts found = shade(*w.in, w.q.hits, 0, 1, w.q.paths, w.q.rays, w.q.keep,
                                    w.q.light_samples, 0, w.q.emissions, 0);
    ASSERT_EQ(found.light_samples, 1u);
    const size_t shadows = light_sample(*w.in, w.q.light_samples, 0, 1, w.q.shadows, 0, w.q.paths);
    ASSERT_EQ(shadows, 1u);
    const SurfaceHit s = surface_at(w.scene, Ray{o, {0, -1, 0}}, hit_at(w.q.hits, 0));
    const Vertex v = surface_vertex(w.scene, s, {0, 1, 0});
    const VertexSamples u = vertex_samples(Sampler{w.config.seed}, 10, sample, 0, true);
    const DirectSample d = next_event(w.scene, *w.lights, w.config.estimator, v, {0, 1, 0}, u);
    ASSERT_TRUE(d.valid);
    EXPECT_EQ(w.q.shadows.path[0], 0u);
    EXPECT_EQ(WAVETRACE_XYZ_AT(w.q.shadows, origin, 0), d.shadow.o);
    EXPECT_EQ(WAVETRACE_XYZ_AT(w.q.shadows, dir, 0), d.shadow.d);
    EXPECT_EQ(w.q.shadows.tmax[0], d.shadow.tmax);
    EXPECT_EQ(WAVETRACE_XYZ_AT(w.q.shadows, contribution, 0), Color(1.0f) * d.value);
    EXPECT_EQ(w.q.shadows.pdf_light[0], d.pdf_light);
    EXPECT_EQ(w.q.shadows.pdf_bsdf[0], d.pdf_bsdf);
    // The same sample by the scalar route (sample_direct) agrees to rounding.
    const DirectSample scalar =
        sample_direct(w.scene, *w.lights, v, {0, 1, 0}, w.lights->select(u.light_select, v.p, v.ng),
                      u.light_u, u.light_v);
    ASSERT_TRUE(scalar.valid);
    EXPECT_NEAR(scalar.pdf_light, d.pdf_light, 1e-5f * d.pdf_light);
}

TEST(Kernels, IntersectShadowSeesBlockersAndCountsRays) {
    World w;
    // From the floor to the light: clear. From below the lower quad up to the light: blocked.
    store_shadow_ray(w.q.shadows, 0, {{0, 1e-3f, 0}, {0, 1, 0}, 0.99f, Color(1.0f), 1.0f, 0.0f, 0});
    store_shadow_ray(w.q.shadows, 1, {{0, -2, 0}, {0, 1, 0}, 2.99f, Color(1.0f), 1.0f, 0.0f, 1});
    generate(*w.in, WaveSamples{}, 0, 0, 2, w.q.paths, w.q.rays);
    const uint64_t rays =
        intersect_shadow(w.bvh, *w.in, w.q.shadows, 0, 2, w.q.transmittance);
    EXPECT_EQ(rays, 2u);
    EXPECT_EQ(w.q.transmittance[0], Color(1.0f));
    EXPECT_EQ(w.q.transmittance[1], Color(0.0f));
}

TEST(Kernels, MisCombineWeightsEachContributionAndAddsItToItsPath) {
    for (Strategy st : {Strategy::Nee, Strategy::Mis}) {
        World w;
        Estimator est = w.config.estimator;
        est.strategy = st;
        est.heuristic = MisHeuristic::Power;
        // Light at infinity by the balance heuristic, as under a compensated environment map.
        const MisHeuristics heuristics{MisHeuristic::Power, MisHeuristic::Balance};
        generate(*w.in, WaveSamples{}, 0, 0, 6, w.q.paths, w.q.rays);
        w.q.paths.radiance[2] = Color(1.0f);
        // Shadow rays with light and BSDF densities 2 and 1 (power heuristic: 4/5), one blocked,
        // one to infinity (balance heuristic: 2/3).
        store_shadow_ray(w.q.shadows, 0, {{}, {}, 1.0f, Color(2, 4, 8), 2.0f, 1.0f, 2});
        store_shadow_ray(w.q.shadows, 1, {{}, {}, 1.0f, Color(1, 1, 1), 2.0f, 1.0f, 0});
        store_shadow_ray(w.q.shadows, 2, {{}, {}, kInfinity, Color(3, 3, 3), 2.0f, 1.0f, 4});
        const Color tr[] = {Color(0.5f, 0.25f, 1.0f), Color(0.0f), Color(1.0f)};  // per channel
        // Emission found by a BSDF-sampled segment (densities 1 and 3: power weight 1/10), by
        // a camera ray (full weight), and by a segment that left the scene (balance: 1/4).
        w.q.emissions.store(0, {3, Color(10, 20, 30), 1.0f, 3.0f, 0});
        w.q.emissions.store(1, {1, Color(5, 5, 5), 0.0f, 0.0f, kCountsFully});
        w.q.emissions.store(2, {5, Color(8, 8, 8), 1.0f, 3.0f, kAtInfinity});
        mis_combine(est, heuristics, w.q.emissions, {0, 3}, w.q.shadows, tr, {0, 3}, w.q.paths);
        const bool mis = st == Strategy::Mis;
        const float ws = mis ? mis_weight(MisHeuristic::Power, 2.0f, 1.0f) : 1.0f;
        const float we = mis ? mis_weight(MisHeuristic::Power, 1.0f, 3.0f) : 0.0f;
        EXPECT_NEAR(ws, mis ? 0.8f : 1.0f, 1e-6f);
        EXPECT_NEAR(we, mis ? 0.1f : 0.0f, 1e-6f);
        EXPECT_EQ(w.q.paths.radiance[0], Color(0.0f));  // blocked
        EXPECT_EQ(w.q.paths.radiance[1], Color(5, 5, 5));
        EXPECT_EQ(w.q.paths.radiance[2],
                  Color(1.0f) + Color(2, 4, 8) * (ws * Color(0.5f, 0.25f, 1.0f)));
        EXPECT_EQ(w.q.paths.radiance[3], Color(10, 20, 30) * we);
        const float ws_inf = mis ? mis_weight(MisHeuristic::Balance, 2.0f, 1.0f) : 1.0f;
        const float we_inf = mis ? mis_weight(MisHeuristic::Balance, 1.0f, 3.0f) : 0.0f;
        EXPECT_NEAR(ws_inf, mis ? 2.0f / 3.0f : 1.0f, 1e-6f);
        EXPECT_NEAR(we_inf, mis ? 0.25f : 0.0f, 1e-6f);
        EXPECT_EQ(w.q.paths.radiance[4], Color(3, 3, 3) * (ws_inf * Color(1.0f)));
        EXPECT_EQ(w.q.paths.radiance[5], Color(8, 8, 8) * we_inf);
    }
}

TEST(Kernels, AccumulateFilmStoresOnlyThePathsThatEnded) {
    World w;
    generate(*w.in, WaveSamples{}, 0, 0, 4, w.q.paths, w.q.rays);
    std::swap(w.q.paths.slot[1], w.q.paths.slot[2]);  // as if sorted: slots travel with paths
    for (size_t i = 0; i < 4; ++i) {
        w.q.paths.radiance[i] = Color(float(i));
        w.q.film.radiance[i] = Color(-1.0f);
    }
    const uint8_t keep[] = {1, 0, 0, 1};
    accumulate_film(w.q.paths, keep, 0, 4, w.q.film);
    EXPECT_EQ(w.q.film.radiance[0], Color(-1.0f));
    EXPECT_EQ(w.q.film.radiance[1], Color(2.0f));
    EXPECT_EQ(w.q.film.radiance[2], Color(1.0f));
    EXPECT_EQ(w.q.film.radiance[3], Color(-1.0f));
}

// A wave's film reaches the image pixel by pixel, each pixel's samples in sample order: the
// film's running sums then equal those of adding the samples one by one in that order.
TEST(Kernels, AddToFilmAddsEachPixelsSamplesInOrder) {
    World w;
    const WaveSamples samples{0, 3};
    WaveFilm wave_film{std::vector<Color>(6)};
    for (size_t i = 0; i < 6; ++i) wave_film.radiance[i] = Color(float(1 + i * i));
    Film film(4, 3), expect(4, 3);
    add_to_film(*w.in, 2, samples, 0, 2, wave_film, film);
    for (uint32_t p = 0; p < 2; ++p)
        for (uint32_t j = 0; j < 3; ++j)
            expect.add(static_cast<int>(pixel_in_pass_order(2 + p, 4, 3)),
                       wave_film.radiance[p * 3 + j]);
    for (int pixel = 0; pixel < 12; ++pixel) {
        EXPECT_EQ(film.samples(pixel), expect.samples(pixel)) << pixel;
        EXPECT_EQ(film.mean().at(pixel % 4, pixel / 4), expect.mean().at(pixel % 4, pixel / 4));
    }
    EXPECT_EQ(film.samples(static_cast<int>(pixel_in_pass_order(2, 4, 3))), 3u);
}

TEST(Kernels, CompactKeepsTheLiveEntriesInOrderAndWhole) {
    World w;
    const size_t n = 9;
    generate(*w.in, WaveSamples{}, 0, 0, n, w.q.paths, w.q.rays);
    std::vector<uint8_t> keep = {0, 1, 1, 0, 0, 1, 0, 1, 0};
    std::vector<Point3> origin(n);
    for (size_t i = 0; i < n; ++i) w.q.rays.origin[i] = origin[i] = {float(i), 0, 0};
    const size_t kept = compact(keep, n, w.q.paths, w.q.rays);
    ASSERT_EQ(kept, 4u);
    const uint32_t expect[] = {1, 2, 5, 7};
    for (size_t k = 0; k < kept; ++k) {
        EXPECT_EQ(w.q.paths.pixel[k], expect[k]);
        EXPECT_EQ(w.q.rays.origin[k], origin[expect[k]]);
    }
    EXPECT_EQ(compact(std::vector<uint8_t>(n, 0), n, w.q.paths, w.q.rays), 0u);
}

// The stage schedule's compaction into a second pair of queues: a part of the kept entries to
// a given place, in order, and nothing else written.
TEST(Kernels, CompactIntoMovesTheKeptEntriesOfARange) {
    World w;
    const size_t n = 9;
    generate(*w.in, WaveSamples{}, 0, 0, n, w.q.paths, w.q.rays);
    WaveQueues next;
    next.resize(16);
    for (size_t i = 0; i < 16; ++i) next.paths.pixel[i] = 99;
    const std::vector<uint8_t> keep = {0, 1, 1, 0, 0, 1, 0, 1, 0};
    // Entries [2, 8) of the wave: 2, 5 and 7 kept, to entries 4, 5, 6.
    ASSERT_EQ(compact_into(keep, 2, 8, w.q.paths, w.q.rays, 4, next.paths, next.rays), 3u);
    const uint32_t expect[] = {99, 99, 99, 99, 2, 5, 7, 99};
    for (size_t k = 0; k < std::size(expect); ++k) EXPECT_EQ(next.paths.pixel[k], expect[k]) << k;
    EXPECT_EQ(next.rays.dir[5], w.q.rays.dir[5]);
}

// Over several of compact's blocks of entries: a block whose entries all stay where they are,
// blocks that lose some, a block that keeps none; every field of every kept entry arrives.
TEST(Kernels, CompactMovesEveryFieldAcrossBlocks) {
    const size_t n = 1000;
    PathQueue paths;
    RayQueue rays;
    paths.resize(n);
    rays.resize(n);
    std::vector<uint8_t> keep(n);
    std::vector<size_t> expect;
    for (size_t i = 0; i < n; ++i) {
        const float f = float(i);
        paths.store(i, PathQueue::Entry{.pixel = uint32_t(i),
                                        .bounce = uint16_t(i % 40),
                                        .depth = uint16_t(i % 37),
                                        .crossings = uint8_t(i % 7),
                                        .counts_fully = uint8_t(i % 2),
                                        .beta = Color(f, f + 0.25f, f + 0.5f),
                                        .radiance = Color(-f),
                                        .prev_p = {f, 2 * f, 3 * f},
                                        .prev_pdf = f + 0.125f,
                                        .media = {},
                                        .flight = f * 0.5f});
        set_ray(rays, i, Ray{{f, -f, 1}, {0, 1, f}});
        keep[i] = i < 300 ? 1 : i >= 768 ? 0 : (i * 7919) % 5 < 3;
        if (keep[i]) expect.push_back(i);
    }
    ASSERT_EQ(compact(keep, n, paths, rays), expect.size());
    for (size_t k = 0; k < expect.size(); ++k) {
        const size_t i = expect[k];
        const float f = float(i);
        ASSERT_EQ(paths.pixel[k], uint32_t(i)) << k;
        EXPECT_EQ(paths.bounce[k], uint16_t(i % 40)) << k;
        EXPECT_EQ(paths.depth[k], uint16_t(i % 37)) << k;
        EXPECT_EQ(paths.crossings[k], uint8_t(i % 7)) << k;
        EXPECT_EQ(paths.counts_fully[k], uint8_t(i % 2)) << k;
        EXPECT_EQ(paths.beta[k], Color(f, f + 0.25f, f + 0.5f)) << k;
        EXPECT_EQ(paths.radiance[k], Color(-f)) << k;
        EXPECT_EQ(paths.prev_p[k], (Point3{f, 2 * f, 3 * f})) << k;
        EXPECT_EQ(paths.prev_pdf[k], f + 0.125f) << k;
        EXPECT_EQ(paths.flight[k], f * 0.5f) << k;
        EXPECT_EQ(rays.origin[k], (Point3{f, -f, 1})) << k;
        EXPECT_EQ(rays.dir[k], (Vec3{0, 1, f})) << k;
    }
}

TEST(Kernels, PackedMediaRoundTrip) {
    for (int size = 0; size <= MediumStack::kMaxNesting; ++size) {
        MediumStack s;
        const MediumId ids[] = {0, kNone, MediumId(kMaxMedia - 1), 12345};
        for (int k = 0; k < size; ++k) s.push(ids[k]);
        const MediumStack back = PackedMedia::pack(s).unpack();
        EXPECT_EQ(back.size, s.size);
        for (int k = 0; k < MediumStack::kMaxNesting; ++k) EXPECT_EQ(back.entries[k], s.entries[k]);
        EXPECT_EQ(back.current(), s.current());
        EXPECT_EQ(PackedMedia::pack(s).current(), s.current());
    }
}

// The queues' bytes per path in flight, from the declarations (docs/architecture.md counts
// them): 130 for the path, its ray and its hit, 157 for a light sample, 60 for a shadow ray, 25
// for emission found, 26 of per-entry scratch and the wave's film. A budget, so that a field
// added is a decision (the last: the previous vertex's normal and its light choice's importance
// sum, with which the MIS weight of the emission its ray finds chooses its light again).
TEST(Kernels, QueuesTakeAtMost398BytesPerPath) {
    EXPECT_LE(wavefront_bytes_per_path(), 398u);
    EXPECT_EQ(wavefront_bytes_per_path(), WaveQueues::bytes_per_path());
}
