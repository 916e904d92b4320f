// Our BVH against Embree 3 on the same rays: camera rays plus rays leaving random surface
// points in cosine-distributed directions, over a million per scene.
#include <gtest/gtest.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "embree/embree_engines.h"
#include "embree/embree_mirror.h"
#include "render_film.h"
#include "sampling/sampler.h"
#include "test_paths.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

constexpr int kCameraSide = 512;            // 262,144 camera rays
constexpr uint32_t kSurfaceRays = 786'432;  // + surface rays = 1,048,576 rays per scene
constexpr float kRelTolerance = 1e-4f;

// Ray i: the first kCameraSide^2 are camera rays through jittered pixel positions; the rest
// leave a random point of a random primitive, on a random side, cosine-distributed.
Ray make_ray(const Scene& scene, const CameraRays& camera, uint32_t i) {
    auto u = [&](uint32_t dim) { return sample_1d(2024, i, 0, dim); };
    const uint32_t camera_rays = kCameraSide * kCameraSide;
    if (i < camera_rays)
        return camera.generate((i % kCameraSide) + u(0), (i / kCameraSide) + u(1), u(2), u(3));

    size_t n = scene.primitive_count();
    size_t flat = std::min(n - 1, static_cast<size_t>(u(4) * static_cast<float>(n)));
    size_t tri = scene.triangles.size(), quad = scene.quads.size();
    Point3 p;
    Normal3 normal;
    float a = u(5), b = u(6);
    if (flat < tri) {
        const Triangle& t = scene.triangles[flat];
        Point3 p0 = scene.positions[t.v[0]], p1 = scene.positions[t.v[1]],
               p2 = scene.positions[t.v[2]];
        float s = std::sqrt(a);  // uniform on the triangle
        p = (1 - s) * p0 + s * (1 - b) * p1 + s * b * p2;
        normal = normalize(cross(p1 - p0, p2 - p0));
    } else if (flat < tri + quad) {
        const Quad& q = scene.quads[flat - tri];
        p = q.q + a * q.u + b * q.v;
        normal = normalize(cross(q.u, q.v));
    } else {
        const Sphere& s = scene.spheres[flat - tri - quad];
        float z = 1 - 2 * a, r = std::sqrt(std::max(0.0f, 1 - z * z)), phi = 2 * kPi * b;
        normal = {r * std::cos(phi), r * std::sin(phi), z};
        p = s.center + s.radius * normal;
    }
    if (u(7) < 0.5f) normal = -normal;
    // Cosine-weighted direction about the chosen side (Malley's method).
    float r = std::sqrt(u(8)), phi = 2 * kPi * u(9);
    Vec3 local{r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1 - r * r))};
    Vec3 d = Frame::from_normal(normal).to_world(local);
    // Start just off the surface so that neither side reports the surface itself.
    float eps = 1e-4f * (max_component(abs(p)) + 1.0f);
    return Ray{p + eps * normal, d};
}

struct Tally {
    size_t rays = 0, both_hit = 0, both_miss = 0, only_ours = 0, only_embree = 0;
    size_t same = 0, ties = 0, different = 0;
    // occluded() of the ray as it is and cut at half Embree's closest hit: where ours and
    // Embree's answers differ.
    size_t occlusion_differs = 0;
    double max_rel_t = 0;  // same primitive, over rays within the relative bound
    // Same primitive, beyond the relative bound but within the one-ulp floor: how many, the
    // largest t among them (in units of the scene's size) and their largest relative difference.
    size_t floor_rays = 0;
    double floor_max_t = 0, floor_max_rel = 0;
    std::vector<uint32_t> examples;  // a few disagreeing rays, for the report

    Tally& operator+=(const Tally& o) {
        rays += o.rays;
        both_hit += o.both_hit;
        both_miss += o.both_miss;
        only_ours += o.only_ours;
        only_embree += o.only_embree;
        same += o.same;
        ties += o.ties;
        different += o.different;
        occlusion_differs += o.occlusion_differs;
        max_rel_t = std::max(max_rel_t, o.max_rel_t);
        floor_rays += o.floor_rays;
        floor_max_t = std::max(floor_max_t, o.floor_max_t);
        floor_max_rel = std::max(floor_max_rel, o.floor_max_rel);
        examples.insert(examples.end(), o.examples.begin(), o.examples.end());
        return *this;
    }
};

void compare_scene(const char* name) {
    Scene scene = load_scene(scene_path(name));
    Bvh bvh = Bvh::build(scene);
    EmbreeMirror embree(scene);
    CameraRays camera(scene.camera, kCameraSide, kCameraSide);
    const double scene_size = length(scene.bounds().extent());
    const uint32_t total = kCameraSide * kCameraSide + kSurfaceRays;

    Tally t = tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(0, total, 4096), Tally{},
        [&](const tbb::blocked_range<uint32_t>& r, Tally acc) {
            for (uint32_t i = r.begin(); i < r.end(); ++i) {
                Ray ray = make_ray(scene, camera, i);
                Hit ours = bvh.intersect(ray), ref = embree.intersect(ray);
                ++acc.rays;
                Ray half = ray;
                if (ref.found()) half.tmax = 0.5f * ref.t;
                acc.occlusion_differs +=
                    (bvh.occluded(ray) != embree.occluded(ray)) +
                    (ref.found() && bvh.occluded(half) != embree.occluded(half));
                if (!ours.found() || !ref.found()) {
                    if (ours.found())
                        ++acc.only_ours;
                    else if (ref.found())
                        ++acc.only_embree;
                    else
                        ++acc.both_miss;
                    if (ours.found() != ref.found() && acc.examples.size() < 3)
                        acc.examples.push_back(i);
                    continue;
                }
                ++acc.both_hit;
                double rel = std::fabs(double(ours.t) - ref.t) / std::max(double(ref.t), 1e-30);
                // Relative 1e-4, with a floor of one float ulp of the hit point's coordinates:
                // no float intersector can place a hit more finely than that (it matters only
                // for rays that start a hair away from another surface).
                Point3 p = ray.at(ref.t);
                double ulp_floor = std::ldexp(double(max_component(abs(p))), -23) / length(ray.d);
                double dt = std::fabs(double(ours.t) - ref.t);
                bool within_rel = dt <= kRelTolerance * ref.t;
                bool t_agrees = dt <= kRelTolerance * ref.t + ulp_floor;
                // A tie: two primitives hit at the same distance (a shared edge, coplanar faces).
                if (ours.prim == ref.prim && t_agrees)
                    ++acc.same;
                else if (t_agrees)
                    ++acc.ties;
                else
                    ++acc.different;
                if (!t_agrees && acc.examples.size() < 3) acc.examples.push_back(i);
                if (ours.prim == ref.prim && within_rel)
                    acc.max_rel_t = std::max(acc.max_rel_t, rel);
                if (ours.prim == ref.prim && !within_rel && t_agrees) {
                    ++acc.floor_rays;
                    acc.floor_max_t =
                        std::max(acc.floor_max_t, double(ref.t) * length(ray.d) / scene_size);
                    acc.floor_max_rel = std::max(acc.floor_max_rel, rel);
                }
            }
            return acc;
        },
        [](Tally a, const Tally& b) { return a += b; });

    double hit_agreement = double(t.both_hit + t.both_miss) / double(t.rays);
    double hit_match = t.both_hit ? double(t.same + t.ties) / double(t.both_hit) : 1.0;
    char line[1024];
    std::snprintf(
        line, sizeof line,
        "embree-agreement %-10s rays %zu | hit/miss agree %.5f%% (both hit %zu, both "
        "miss %zu, only ours %zu, only embree %zu) | both hit: same prim+t %zu, ties "
        "%zu, differ %zu (%.5f%% agree) | occluded() differs %zu | same prim: max rel t diff "
        "%.2e; %zu rays "
        "beyond 1e-4 relative but within it plus one float ulp of the hit point (rel diff up "
        "to %.1e, all at t < %.1e x scene size: origins a hair from another surface)\n",
        name, t.rays, 100 * hit_agreement, t.both_hit, t.both_miss, t.only_ours, t.only_embree,
        t.same, t.ties, t.different, 100 * hit_match, t.occlusion_differs, t.max_rel_t,
        t.floor_rays, t.floor_max_rel, t.floor_max_t);
    std::fputs(line, stdout);
    // Also into the build's report folder, which `make test` prints after the suite: ctest
    // shows a passing test's output only when asked to be verbose.
    std::filesystem::create_directories(WAVETRACE_REPORT_DIR);
    std::ofstream(std::filesystem::path(WAVETRACE_REPORT_DIR) /
                  ("embree-agreement-" + std::string(name) + ".txt"))
        << line;
    for (size_t k = 0; k < std::min<size_t>(t.examples.size(), 8); ++k) {
        Ray ray = make_ray(scene, camera, t.examples[k]);
        Hit ours = bvh.intersect(ray), ref = embree.intersect(ray);
        std::printf(
            "  ray %u o (%g %g %g) d (%g %g %g): ours kind %u prim %u t %.7g | embree kind %u prim "
            "%u t %.7g\n",
            t.examples[k], ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z,
            static_cast<unsigned>(ours.prim.kind()), ours.prim.index(), ours.t,
            static_cast<unsigned>(ref.prim.kind()), ref.prim.index(), ref.t);
    }
    EXPECT_GE(t.rays, 1'000'000u);
    EXPECT_GE(hit_agreement, 0.9999) << name;
    EXPECT_GE(hit_match, 0.9999) << name;
    EXPECT_LE(t.occlusion_differs, t.rays / 10000) << name;
    EXPECT_GT(t.both_hit, t.rays / 2) << name << ": too few hits for the test to mean much";
    EXPECT_LE(t.max_rel_t, kRelTolerance) << name;
    // The ulp floor is for rays that meet a surface right after leaving another one; it must
    // stay rare and confined to tiny t.
    EXPECT_LE(t.floor_rays, t.both_hit / 1000) << name;
    EXPECT_LE(t.floor_max_t, 1e-3) << name;
}

}  // namespace

TEST(EmbreeAgreement, Cornell) {
    compare_scene("cornell");
}
TEST(EmbreeAgreement, Bunny) {
    compare_scene("bunny");
}
TEST(EmbreeAgreement, Dragon) {
    compare_scene("dragon");
}
TEST(EmbreeAgreement, Everything) {
    compare_scene("everything");
}
// Alpha masks on a sphere (a uv checkerboard), a quad and a mesh (an image): Embree's filter
// functions against our traversals.
TEST(EmbreeAgreement, MaskedMaterials) {
    compare_scene("materials");
}

namespace {

// Per-channel comparison of two images: how many values differ by more than `rel` (relative,
// with a 1e-6 absolute floor), and the relative difference of the image means.
struct ImageDiff {
    size_t outside = 0, values = 0;
    double mean_rel = 0;
};
ImageDiff diff_images(const Image& a, const Image& b, double rel) {
    ImageDiff d;
    double sum_a = 0, sum_b = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        for (int k = 0; k < 3; ++k) {
            double x = a.pixels[i][k], y = b.pixels[i][k];
            sum_a += x;
            sum_b += y;
            ++d.values;
            double diff = std::fabs(x - y);
            if (diff > 1e-6 && diff > rel * std::fabs(x)) ++d.outside;
        }
    d.mean_rel = std::fabs(sum_a - sum_b) / std::max(sum_a, 1e-30);
    return d;
}

}  // namespace

// Each engine with Embree as its intersector: the wavefront equals the megakernel exactly as
// with our BVH (same paths), and both give our BVH's image except where the intersectors
// round a hit point differently, which moves a path by a few ulps.
TEST(EmbreeEngines, SameImagesAsWithOurBvh) {
    for (const char* name : {"cornell", "cornell-smoke", "bunny", "everything"}) {
        Scene scene = load_scene(scene_path(name));
        Bvh bvh = Bvh::build(scene);
        EmbreeMirror embree(scene);
        RenderRequest c;
        c.width = 40;
        c.height = 40;
        c.spp = 4;
        c.seed = 5;
        c.estimator.max_depth = scene.render.max_depth;
        WavefrontOptions wf;
        wf.wave_size = 700;
        Image mk_ours = megakernel_film(scene, bvh, c).mean();
        Image mk_embree = megakernel_film(scene, embree, c).mean();
        Image wf_embree = wavefront_film(scene, embree, c, wf).mean();
        ImageDiff engines = diff_images(mk_embree, wf_embree, 1e-4);
        ImageDiff intersectors = diff_images(mk_ours, mk_embree, 1e-3);
        std::printf(
            "embree-engines %-13s wavefront vs megakernel (both Embree): %zu/%zu values beyond "
            "1e-4, means %.1e | Embree vs our BVH (megakernel): %zu/%zu beyond 1e-3, means "
            "%.1e\n",
            name, engines.outside, engines.values, engines.mean_rel, intersectors.outside,
            intersectors.values, intersectors.mean_rel);
        EXPECT_LE(engines.outside, engines.values / 1000) << name;
        EXPECT_LE(engines.mean_rel, 1e-5) << name;
        EXPECT_LE(intersectors.outside, intersectors.values / 50) << name;
        EXPECT_LE(intersectors.mean_rel, 1e-4) << name;
    }
}
