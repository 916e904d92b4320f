// Traversal and build as a scene outgrows the caches: 10^4 to 10^7 triangles made of the
// Stanford dragon (scenes/dragon.json's 100,000 triangles; below that a coarser dragon by
// vertex clustering, above it a grid of rotated, scaled copies baked into one mesh), our BVH
// beside Embree's on the same captured batches as the BVH section, with build times, bytes per
// triangle and the process's peak memory.
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>

#include "embree/embree_engines.h"
#include "embree/embree_mirror.h"
#include "ray_batches.h"
#include "sections.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

namespace {

struct TriangleMesh {
    std::vector<Point3> positions;
    std::vector<uint32_t> indices;  // three per triangle
    size_t triangles() const { return indices.size() / 3; }
};

// The scene's mesh of most triangles (the dragon of scenes/dragon.json), world positions.
TriangleMesh largest_mesh(const Scene& s) {
    std::vector<size_t> count(s.meshes.size());
    for (const Triangle& t : s.triangles) ++count[t.mesh];
    const size_t m = std::max_element(count.begin(), count.end()) - count.begin();
    const Mesh& mesh = s.meshes[m];
    TriangleMesh out;
    out.positions.assign(s.positions.begin() + mesh.first_vertex,
                         s.positions.begin() + mesh.first_vertex + mesh.vertex_count);
    for (const Triangle& t : s.triangles)
        if (t.mesh == m)
            for (uint32_t v : t.v) out.indices.push_back(v - mesh.first_vertex);
    return out;
}

// Vertex clustering (Rossignac & Borrel 1993): the vertices in each cube of a grid of `cells`
// cubes along the mesh's longest side merge into their mean, and the triangles that lose a
// corner to a merge go.
TriangleMesh clustered(const TriangleMesh& m, int cells) {
    Aabb box;
    for (const Point3& p : m.positions) box.grow(p);
    const Vec3 extent = box.hi - box.lo;
    const float side = std::max({extent.x, extent.y, extent.z}) / float(cells);
    std::map<std::tuple<int, int, int>, uint32_t> cluster_of_cell;
    std::vector<uint32_t> cluster(m.positions.size());
    std::vector<Vec3> sum;
    std::vector<int> members;
    for (size_t i = 0; i < m.positions.size(); ++i) {
        const Vec3 d = (m.positions[i] - box.lo) / side;
        const auto cell = std::make_tuple(int(d.x), int(d.y), int(d.z));
        auto [it, added] = cluster_of_cell.try_emplace(cell, uint32_t(sum.size()));
        if (added) {
            sum.push_back(Vec3{0.0f, 0.0f, 0.0f});
            members.push_back(0);
        }
        cluster[i] = it->second;
        sum[it->second] += m.positions[i];
        ++members[it->second];
    }
    TriangleMesh out;
    for (size_t c = 0; c < sum.size(); ++c) out.positions.push_back(sum[c] / float(members[c]));
    for (size_t t = 0; t < m.triangles(); ++t) {
        const uint32_t a = cluster[m.indices[3 * t]], b = cluster[m.indices[3 * t + 1]],
                       c = cluster[m.indices[3 * t + 2]];
        if (a != b && b != c && a != c) out.indices.insert(out.indices.end(), {a, b, c});
    }
    return out;
}

// The clustering of `m` whose triangle count is nearest `target` (bisection on the grid).
TriangleMesh coarsened(const TriangleMesh& m, size_t target) {
    int lo = 2, hi = 4096;
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        (clustered(m, mid).triangles() < target ? lo : hi) = mid;
    }
    TriangleMesh a = clustered(m, lo), b = clustered(m, hi);
    const auto miss = [&](const TriangleMesh& x) {
        return std::fabs(double(x.triangles()) - double(target));
    };
    return miss(a) <= miss(b) ? a : b;
}

// A scene of about `target` triangles: the coarsened dragon below its own count, else a
// square grid of round(target / its count) copies, each turned about y and scaled by its own
// (golden-ratio) amounts, on a floor under a square area light, seen from above at an angle.
Scene grown_scene(const TriangleMesh& dragon, size_t target) {
    const TriangleMesh base = target < dragon.triangles() ? coarsened(dragon, target) : dragon;
    const size_t copies = std::max<size_t>(1, std::llround(double(target) / base.triangles()));
    const int grid = int(std::ceil(std::sqrt(double(copies))));
    Aabb box;
    for (const Point3& p : base.positions) box.grow(p);
    const Vec3 extent = box.hi - box.lo;
    const Point3 center = box.lo + 0.5f * extent;
    const float spacing = 1.25f * std::max(extent.x, extent.z);
    TriangleMesh all;
    for (size_t k = 0; k < copies; ++k) {
        const float turn = 2.0f * kPi * float(std::fmod(0.6180339887 * double(k), 1.0));
        const float scale = 0.8f + 0.4f * float(std::fmod(0.7548776662 * double(k), 1.0));
        const float cx = spacing * float(k % grid), cz = spacing * float(k / grid);
        const float c = std::cos(turn), s = std::sin(turn);
        const uint32_t first = uint32_t(all.positions.size());
        for (const Point3& p : base.positions) {
            const Vec3 d = scale * (p - center);
            all.positions.push_back({center.x + cx + c * d.x + s * d.z, center.y + d.y,
                                     center.z + cz - s * d.x + c * d.z});
        }
        for (uint32_t i : base.indices) all.indices.push_back(first + i);
    }
    Scene scene;
    Material grey;
    grey.albedo = scene.add_solid(Color(0.6f));
    Mesh mesh;
    mesh.name = "dragons";
    mesh.material = scene.add_material(grey);
    scene.add_mesh(mesh, all.positions, {}, {}, all.indices);
    // The floor and the light span the grid with a margin of one spacing.
    const float width = spacing * float(grid + 1);
    const Point3 corner{center.x - spacing, box.lo.y, center.z - spacing};
    Material floor;
    floor.albedo = scene.add_solid(Color(0.4f));
    scene.add_quad({corner, {0, 0, width}, {width, 0, 0}, scene.add_material(floor), kNone});
    Material light;
    light.kind = MaterialKind::DiffuseLight;
    light.emission = scene.add_solid(Color(4.0f));
    scene.add_quad({corner + Vec3{0, 2.0f * extent.y + width, 0},
                    {width, 0, 0},
                    {0, 0, width},
                    scene.add_material(light),
                    kNone});
    const Point3 middle = corner + Vec3{0.5f * width, 0.5f * extent.y, 0.5f * width};
    scene.camera.look_at = middle;
    scene.camera.look_from = middle + Vec3{0.0f, 0.7f * width, -1.3f * width};
    scene.camera.vfov = 40.0f;
    return scene;
}

double peak_rss_mib() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;  // KiB on Linux
}

}  // namespace

void bench_scene_size(const Options& o, Results& r) {
    r.table("scene_size", {"triangles", "batch", "threads", "rays", "ours_mrays", "embree_mrays",
                           "ours_over_embree", "ours_packet_mrays", "embree_packet16_mrays",
                           "ours_packet_over_embree_packet16"});
    r.table("scene_size_build",
            {"triangles", "ours_ms", "embree_medium_ms", "embree_high_ms", "ours_over_embree_high",
             "ours_bytes_per_triangle", "ours_traversal_bytes_per_triangle",
             "embree_medium_bytes_per_triangle", "embree_high_bytes_per_triangle", "peak_rss_mib"});
    r.table("scene_size_render", {"triangles", "threads", "megakernel_mpaths", "wavefront_mpaths",
                                  "wavefront_over_megakernel", "megakernel_embree_mpaths",
                                  "wavefront_embree_mpaths", "megakernel_ours_over_embree"});
    const TriangleMesh dragon = largest_mesh(load_scene(o.scenes / "dragon.json"));
    const int all_threads = tbb::this_task_arena::max_concurrency();
    const std::vector<size_t> sizes =
        !o.triangles.empty() ? o.triangles
        : o.quick            ? std::vector<size_t>{10'000}
                             : std::vector<size_t>{10'000, 100'000, 1'000'000, 10'000'000};
    for (size_t target : sizes) {
        const Scene scene = grown_scene(dragon, target);
        const size_t n = scene.triangles.size();
        // Builds on all threads; the largest scene's once (they take seconds), the others'
        // the median of three.
        const int builds = n > 2'000'000 ? 1 : 3;
        const double ours_ms =
            median_ms([&] { return Bvh::build(scene).stats().build_ms; }, builds);
        const double medium_ms = median_ms(
            [&] { return EmbreeMirror(scene, RTC_BUILD_QUALITY_MEDIUM, false).build_ms(); },
            builds);
        double high_bytes = 0;
        const double high_ms = median_ms(
            [&] {
                EmbreeMirror high(scene, RTC_BUILD_QUALITY_HIGH, false);
                high_bytes = double(high.bytes() - high.geometry_bytes());
                return high.build_ms();
            },
            builds);
        const Bvh bvh = Bvh::build(scene);
        const EmbreeMirror embree(scene, RTC_BUILD_QUALITY_MEDIUM, /*robust=*/false);
        const BvhStats& st = bvh.stats();
        const double per = 1.0 / double(n);
        const double ours_bytes = double(st.bytes + st.wide_bytes) * per,
                     traversal_bytes = double(st.wide_bytes) * per,
                     embree_bytes = double(embree.bytes() - embree.geometry_bytes()) * per;
        std::printf(
            "scene_size %9zu triangles: build ours %8.1f ms, embree medium %8.1f, high %8.1f; "
            "bytes/triangle ours %.1f (traversal %.1f), embree medium %.1f, high %.1f\n",
            n, ours_ms, medium_ms, high_ms, ours_bytes, traversal_bytes, embree_bytes,
            high_bytes * per);
        const Batches b = capture(scene, bvh, o.quick ? 32 : 512);
        for (int threads : {1, all_threads}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            time_batches(bvh, embree, b, threads, o.repetitions(),
                         [&](const char* batch, size_t rays, const BatchRates& t) {
                             nlohmann::json ours_p = nullptr, p16 = nullptr, ratio_p = nullptr;
                             if (t.packets) {
                                 ours_p = t.ours_packet;
                                 p16 = t.embree_packet16;
                                 ratio_p = t.ours_packet_over_embree16;
                             }
                             r.row("scene_size", {n, batch, threads, rays, t.ours, t.embree,
                                                  t.ours_over_embree, ours_p, p16, ratio_p});
                             std::printf(
                                 "scene_size %9zu %-8s %d thread(s): ours %7.2f Mrays/s, "
                                 "embree %7.2f, ours/embree %.2f\n",
                                 n, batch, threads, t.ours, t.embree, t.ours_over_embree);
                             std::fflush(stdout);
                         });
        }
        // Renders on all threads, both engines on both BVHs, interleaved: paths of up to eight
        // segments under the area light.
        {
            RenderRequest cfg;
            cfg.width = cfg.height = o.quick ? 16 : 256;
            cfg.spp = o.quick ? 1 : 2;
            cfg.seed = 1;
            cfg.sampler = o.sampler;
            cfg.estimator.max_depth = 8;
            std::vector<double> mk, wf, mke, wfe, wf_over_mk, mk_over_mke;
            for (int rep = 0; rep < o.repetitions(); ++rep) {
                const RenderStats m = render_once(scene, bvh, cfg, Engine::Megakernel),
                                  w = render_once(scene, bvh, cfg, Engine::Wavefront),
                                  me = render_once(scene, embree, cfg, Engine::Megakernel),
                                  we = render_once(scene, embree, cfg, Engine::Wavefront);
                mk.push_back(m.paths / m.seconds * 1e-6);
                wf.push_back(w.paths / w.seconds * 1e-6);
                mke.push_back(me.paths / me.seconds * 1e-6);
                wfe.push_back(we.paths / we.seconds * 1e-6);
                wf_over_mk.push_back(m.seconds / w.seconds);
                mk_over_mke.push_back(me.seconds / m.seconds);
            }
            r.row("scene_size_render",
                  {n, all_threads, spread(mk).median, spread(wf).median, spread(wf_over_mk).median,
                   spread(mke).median, spread(wfe).median, spread(mk_over_mke).median});
            std::printf(
                "scene_size %9zu render %d thread(s): megakernel %6.3f Mpaths/s, wavefront %6.3f "
                "(%.2fx); on Embree %6.3f, %6.3f\n",
                n, all_threads, spread(mk).median, spread(wf).median, spread(wf_over_mk).median,
                spread(mke).median, spread(wfe).median);
        }
        r.row("scene_size_build",
              {n, ours_ms, medium_ms, high_ms, ours_ms / high_ms, ours_bytes, traversal_bytes,
               embree_bytes, high_bytes * per, peak_rss_mib()});
    }
}

}  // namespace wavetrace::bench
