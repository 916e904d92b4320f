// The formulas written once over lanes (src/math/lanes-inl.h and the -inl.h files that use it):
// their vector instances give the one-lane instance's bits on every SIMD target, which is what
// lets the two engines trace the same paths; and the shared polynomial is accurate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "accel/wide_bvh.h"
#include "blocks/lane_kernels.h"
#include "math/erf-inl.h"
#include "math/lanes-inl.h"
#include "sampling/distribution-inl.h"
#include "sampling/pixel_filter-inl.h"
#include "sampling/sampler.h"
#include "sampling/warp.h"
#include "shading/lane_routes.h"
#include "shading/lights.h"
#include "shading/mis.h"
#include "shading/path_vertex.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/camera.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;
namespace lanes = wavetrace::HWY_NAMESPACE;  // the one-lane instances (static target)
using lanes::OneLane;

namespace {

bool same_bits(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same_bits(Vec3 a, Vec3 b) {
    return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

Vec3 unit(float u1, float u2) {
    return sample_uniform_sphere(u1, u2);
}

// The lane vertices (is_lane_vertex) the tests cover, in sixths of their rows, or sevenths with
// the delta lobes (which take no light sample).
enum class LaneKind { Lambertian, Metal, Conductor, Dielectric, MetallicRoughness, Medium, Delta };
LaneKind lane_kind(size_t i, size_t n, bool with_delta = false) {
    return static_cast<LaneKind>((with_delta ? 7 : 6) * i / n);
}

// A Lambertian, rough metal, rough conductor, rough dielectric or metallic-roughness surface
// vertex at p, its normals, albedo and roughness from dimensions 3-9 and 21 of u (a conductor's
// or a dielectric's index of refraction and distribution, or a metallic-roughness surface's
// IOR, metallic, clearcoat, one-sidedness and transmission from 22-29): the shading normal tilted
// off the geometric one, so that the geometric-side tests reject some directions. Or a vertex in a
// medium of isotropic phase function, as medium_vertex() makes it.
template <class Dim>
Vertex lane_vertex_at(Point3 p, Dim u, LaneKind kind) {
    Vertex v;
    v.p = p;
    v.bsdf.albedo = {u(7), u(8), u(9)};
    if (kind == LaneKind::Medium) {
        v.frame = Frame::from_normal({0, 0, 1});
        v.bsdf.kind = MaterialKind::Isotropic;
        return v;
    }
    v.ng = unit(u(3), u(4));
    v.frame = Frame::from_normal(normalize(v.ng + 0.3f * unit(u(5), u(6))));
    if (kind == LaneKind::Lambertian) return v;
    if (kind == LaneKind::Delta) {  // a mirror, a smooth metal, conductor or dielectric
        const MaterialKind kinds[] = {MaterialKind::Mirror, MaterialKind::Metal,
                                      MaterialKind::Conductor, MaterialKind::Dielectric};
        v.bsdf.kind = kinds[std::min(3, int(4 * u(29)))];
        v.bsdf.eta = 1.1f + u(22);
        v.bsdf.conductor_eta = {0.1f + 2.0f * u(22), 0.1f + 2.0f * u(23), 0.1f + 2.0f * u(24)};
        v.bsdf.conductor_k = {5.0f * u(25), 5.0f * u(26), 5.0f * u(27)};
        return v;
    }
    v.bsdf.alpha = 0.02f + 0.6f * u(21);
    if (kind == LaneKind::Metal) {
        v.bsdf.kind = MaterialKind::Metal;
        return v;
    }
    v.bsdf.alpha_v = v.bsdf.alpha;
    if (kind == LaneKind::Dielectric) {  // seen from outside or inside, of either distribution
        v.bsdf.kind = MaterialKind::Dielectric;
        v.bsdf.eta = 1.1f + u(22);
        v.bsdf.distribution = u(28) < 0.5f ? Microfacet::Beckmann : Microfacet::Ggx;
        return v;
    }
    if (kind == LaneKind::MetallicRoughness) {
        v.bsdf.kind = MaterialKind::MetallicRoughness;
        v.bsdf.eta = 1.2f + u(22);
        v.bsdf.metallic = u(23) < 0.3f ? 1.0f : u(23) < 0.6f ? 0.0f : u(24);
        v.bsdf.clearcoat = u(25) < 0.5f ? 0.0f : u(25);
        v.bsdf.clearcoat_alpha = 0.01f + 0.3f * u(26);
        v.bsdf.one_sided = u(27) < 0.5f;
        v.bsdf.transmission = u(29) < 0.5f ? 0.0f : u(29);  // thin-walled
        return v;
    }
    v.bsdf.kind = MaterialKind::Conductor;
    v.bsdf.conductor_eta = {0.1f + 2.0f * u(22), 0.1f + 2.0f * u(23), 0.1f + 2.0f * u(24)};
    v.bsdf.conductor_k = {5.0f * u(25), 5.0f * u(26), 5.0f * u(27)};
    v.bsdf.distribution = u(28) < 0.5f ? Microfacet::Beckmann : Microfacet::Ggx;
    return v;
}

// Lambertian, rough metal, rough conductor, metallic-roughness and medium vertices around the
// lights of `scene`, quads, triangles, spheres and an environment map (the vertices outside the
// spheres): the vector light samples give next_event's shadow rays, unweighted contributions
// (times beta) and densities bit for bit, packed in row order. Counts in *spheres the rows whose
// light was a sphere, in *maps those whose light was the environment map.
void expect_light_samples_are_next_event(const Scene& scene,
                                         size_t* spheres,
                                         size_t* maps = nullptr,
                                         size_t* deltas = nullptr) {
    const LightSet lights(scene);
    const size_t n = 59;
    struct Case {
        Vertex v;
        Vec3 wo;
        Color beta;
        VertexSamples u;
    };
    std::vector<Case> cases;
    for (uint32_t i = 0; i < n; ++i) {
        auto u = [&](uint32_t d) { return sample_1d(13, i, 0, d); };
        Case c;
        c.v = lane_vertex_at(Vec3{4 * u(0) - 2, 4 * u(1) - 2, 4 * u(2) - 2}, u, lane_kind(i, n));
        c.wo = unit(u(10), u(11));
        c.beta = Color(2.0f * u(12));
        c.u.light_select = u(13);
        c.u.light_u = u(14);
        c.u.light_v = u(15);
        cases.push_back(c);
    }
    size_t appended = 0, skipped = 0;
    *spheres = 0;
    size_t environment_rows = 0, delta_rows = 0;
    Estimator config;
    config.strategy = Strategy::Mis;
    for (int64_t target : wide_simd_targets()) {
        use_wide_simd_target(target);
        SCOPED_TRACE(wide_simd_target());
        LightSampleQueue queue;
        queue.resize(n);
        LightSampleBlock block;
        block.queue = &queue;
        block.first = 0;
        block.n = n;
        for (size_t k = 0; k < n; ++k) {
            const Case& c = cases[k];
            ASSERT_TRUE(samples_lights(config, c.v, lights));
            const LightChoice light = lights.select(c.u.light_select, c.v.p, c.v.ng);
            const int32_t planar = planar_light_sample_at(c.v, lights, light);
            const int32_t sphere = planar < 0 ? sphere_light_sample_at(c.v, lights, light) : -1;
            const int32_t delta = delta_light_sample_at(is_lane_vertex(c.v), lights, light);
            const bool map = planar < 0 && sphere < 0 && delta < 0 &&
                             environment_light_sample_at(c.v, lights, light);
            ASSERT_TRUE(planar >= 0 || sphere >= 0 || delta >= 0 || map);
            *spheres += sphere >= 0;
            delta_rows += delta >= 0;
            environment_rows += map;
            block.environment[k] = map ? 1 : 0;
            block.delta[k] = delta;
            store_queued_vertex(queue, k,
                                {uint32_t(k),
                                 c.v.p,
                                 c.v.ng,
                                 c.v.frame.n,
                                 c.v.frame_angle,
                                 c.v.unbent,
                                 c.v.bump_alpha2,
                                 c.wo,
                                 c.v.bsdf.albedo,
                                 c.v.bsdf.alpha,
                                 c.v.bsdf.alpha_v,
                                 c.v.bsdf.metallic,
                                 c.v.bsdf.coat_normal,
                                 c.v.uv,
                                 c.v.bsdf.kind,
                                 kNone,
                                 c.beta,
                                 c.u.light_select,
                                 c.u.light_u,
                                 c.u.light_v});
            block.lobe[k] = int32_t(lane_lobe(c.v.bsdf.kind));
            if (c.v.bsdf.kind == MaterialKind::Conductor ||
                c.v.bsdf.kind == MaterialKind::Dielectric ||
                c.v.bsdf.kind == MaterialKind::MetallicRoughness)
                block.glossy.set(k, c.v.bsdf);
            block.planar[k] = planar;
            block.sphere[k] = sphere;
            block.select_prob[k] = light.probability;
        }
        ShadowQueue shadows;
        shadows.resize(n + 1);
        shadows.path[n] = 12345;  // past the rows' shadows: left alone
        const size_t count = sample_lights_in_lanes(block, lights, shadows, 0);
        size_t s = 0;  // the valid rows' shadow rays, in row order
        for (size_t k = 0; k < n; ++k) {
            const Case& c = cases[k];
            const DirectSample d = next_event(scene, lights, config, c.v, c.wo, c.u);
            if (!d.valid) {
                ++skipped;
                continue;
            }
            ++appended;
            ASSERT_LT(s, count) << "row " << k;
            ASSERT_EQ(shadows.path[s], k);
            EXPECT_TRUE(same_bits(d.shadow.o, WAVETRACE_XYZ_AT(shadows, origin, s))) << "row " << k;
            EXPECT_TRUE(same_bits(d.shadow.d, WAVETRACE_XYZ_AT(shadows, dir, s))) << "row " << k;
            EXPECT_TRUE(same_bits(d.shadow.tmax, shadows.tmax[s])) << "row " << k;
            EXPECT_TRUE(same_bits(c.beta * d.value, WAVETRACE_XYZ_AT(shadows, contribution, s)))
                << "row " << k;
            EXPECT_TRUE(same_bits(d.pdf_light, shadows.pdf_light[s])) << "row " << k;
            EXPECT_TRUE(same_bits(d.pdf_bsdf, shadows.pdf_bsdf[s])) << "row " << k;
            ++s;
        }
        EXPECT_EQ(s, count);
        EXPECT_EQ(shadows.path[n], 12345u);
    }
    use_wide_simd_target(0);
    if (maps) *maps = environment_rows;
    if (deltas) *deltas = delta_rows;
    EXPECT_GT(appended, 0u);
    EXPECT_GT(skipped, 0u);  // back faces, directions below the surface
}

// A latitude-longitude or equal-area environment map of w x h texels: a bright spot, a
// gradient and a black band, scaled per channel, turned by a frame.
void add_environment(Scene& scene, int w, int h, bool equal_area) {
    ImageData image;
    image.path = "environment";
    image.width = w;
    image.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float spot = (x == w / 3 && y == h / 4) ? 500.0f : 0.0f;
            const float band = y == h / 2 ? 0.0f : 1.0f;
            image.texels.push_back(Color(spot + band * (0.1f + float(x) / float(w)),
                                         band * float(y) / float(h), 0.3f * band));
        }
    Background& bg = scene.background;
    bg.kind = Background::Kind::Environment;
    bg.image = scene.add_image(std::move(image));
    bg.radiance = {2.0f, 1.5f, 1.0f};
    bg.mapping = equal_area ? Background::Mapping::EqualArea : Background::Mapping::LatLong;
    bg.rotation = 30.0f;
    bg.frame = Frame{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};
}

// Two emitting materials: one-sided and brighter, two-sided and dimmer.
std::pair<MaterialId, MaterialId> add_emitters(Scene& scene) {
    Material one_sided;
    one_sided.kind = MaterialKind::DiffuseLight;
    one_sided.emission = scene.add_solid({4, 3, 2});
    Material two_sided = one_sided;
    two_sided.emission = scene.add_solid({1, 1, 1});
    two_sided.two_sided = true;
    return {scene.add_material(one_sided), scene.add_material(two_sided)};
}

}  // namespace

TEST(Lanes, Atan2AndAcosAreAccurate) {
    // Against libm in double, around the circle (every octant and its edges) and over [-1, 1].
    double worst_atan = 0, worst_acos = 0;
    for (int i = 0; i <= 1 << 14; ++i) {
        const double angle = 2.0 * M_PI * i / (1 << 14) - M_PI;
        for (const double r : {1e-3, 1.0, 7e4}) {
            const float y = float(r * std::sin(angle)), x = float(r * std::cos(angle));
            const double error =
                std::abs(lanes::Atan2<OneLane>(y, x) - std::atan2(double(y), double(x)));
            worst_atan = std::max(worst_atan, std::min(error, 2.0 * M_PI - error));
        }
        const float c = std::clamp(float(2.0 * i / (1 << 14) - 1.0), -1.0f, 1.0f);
        worst_acos =
            std::max(worst_acos, std::abs(lanes::Acos<OneLane>(c) - std::acos(double(c))));
    }
    EXPECT_LT(worst_atan, 4e-7);
    EXPECT_LT(worst_acos, 4e-7);
    EXPECT_EQ(lanes::Atan2<OneLane>(0.0f, 0.0f), 0.0f);
    EXPECT_EQ(lanes::Atan2<OneLane>(0.0f, 1.0f), 0.0f);
    EXPECT_FLOAT_EQ(lanes::Atan2<OneLane>(1.0f, 0.0f), float(M_PI / 2));
    EXPECT_FLOAT_EQ(lanes::Atan2<OneLane>(0.0f, -1.0f), float(M_PI));
    EXPECT_EQ(lanes::Acos<OneLane>(1.0f), 0.0f);
    EXPECT_FLOAT_EQ(lanes::Acos<OneLane>(-1.0f), float(M_PI));
}

TEST(Lanes, SinCosOfTheWarpsIsAccurate) {
    // sample_cosine_hemisphere's azimuth comes from the shared polynomial: compare it with
    // libm's in double over a fine grid of u2 (u1 = 1: the point is (cos, sin, 0)).
    double worst = 0;
    for (int i = 0; i <= 1 << 16; ++i) {
        const float u2 = std::nextafter(float(i) / float(1 << 16), 0.0f);
        const Vec3 w = sample_cosine_hemisphere(1.0f, u2);
        const double phi = 2.0 * M_PI * double(u2);
        worst = std::max({worst, std::fabs(w.x - std::cos(phi)), std::fabs(w.y - std::sin(phi))});
    }
    EXPECT_LT(worst, 2.5e-7);  // about 2 ulps of 1; the argument 2 pi u2 alone rounds 0.5 ulp
}

TEST(Lanes, FrameAndOriginOffsetKeepTheirFormulas) {
    for (uint32_t i = 0; i < 2000; ++i) {
        const Vec3 n = unit(sample_1d(3, i, 0, 0), sample_1d(3, i, 0, 1));
        const Frame f = Frame::from_normal(n);
        EXPECT_NEAR(dot(f.s, f.t), 0.0f, 1e-6f);
        EXPECT_NEAR(dot(f.s, n), 0.0f, 1e-6f);
        EXPECT_NEAR(dot(cross(f.s, f.t), n), 1.0f, 1e-5f);  // right-handed
        const Point3 p = n * (1000.0f * sample_1d(3, i, 0, 2));
        EXPECT_EQ(origin_offset(p), 2e-5f * (1.0f + max_component(abs(p))));
    }
}

TEST(Lanes, VertexSamplesAreTheScalarOnesOnEverySimdTarget) {
    const size_t n = 61;  // not a multiple of any lane count
    uint32_t pixel[kShadeChunk], sample[kShadeChunk];
    uint16_t bounce[kShadeChunk];
    for (size_t k = 0; k < n; ++k) {
        pixel[k] = static_cast<uint32_t>(k * 7919 + (k << 20));
        bounce[k] = static_cast<uint16_t>(k % 9);
        sample[k] = static_cast<uint32_t>(13 + k % 7);  // across ZSobol's blocks of 8
    }
    for (int64_t target : wide_simd_targets()) {
        use_wide_simd_target(target);
        for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol})
            for (bool one_sample : {true, false}) {
                SCOPED_TRACE(std::string(wide_simd_target()) + " " + to_string(kind) +
                             (one_sample ? " one-sample pairs" : ""));
                const Sampler sampler{42, kind, 37, 23, 3};
                SampleBlock block;
                draw_vertex_samples(sampler, sample, pixel, bounce, n, one_sample, true, block);
                for (size_t k = 0; k < n; ++k) {
                    const VertexSamples one =
                        vertex_samples(sampler, pixel[k], sample[k], bounce[k], one_sample);
                    const VertexSamples lanes = block.at(k);
                    ASSERT_EQ(std::memcmp(&one, &lanes, sizeof one), 0) << "row " << k;
                    ASSERT_TRUE(same_bits(one.light_select,
                                          sample_1d(sampler, pixel[k], sample[k],
                                                    bounce_dim(bounce[k], kDimLightSelect))));
                    // The optical depth of the segment the vertex starts: segment_flight's.
                    const float u = sample_1d(sampler, pixel[k], sample[k],
                                              bounce_dim(bounce[k] + 1, kDimMediumDistance));
                    ASSERT_TRUE(same_bits(block.next_flight[k], sample_free_flight(1.0f, u)))
                        << "row " << k;
                    // The megakernel draws it with the vertex's pairs when it asks for it.
                    float next_flight = -1.0f;
                    const VertexSamples with_flight = vertex_samples(
                        sampler, pixel[k], sample[k], bounce[k], one_sample, &next_flight);
                    ASSERT_EQ(std::memcmp(&one, &with_flight, sizeof one), 0) << "row " << k;
                    ASSERT_TRUE(same_bits(next_flight, block.next_flight[k])) << "row " << k;
                }
            }
    }
    use_wide_simd_target(0);
}

// Lambertian vertices, then rough metal ones, then medium ones (so that vectors hold one kind or
// two), with random normals (lane_vertex_at), throughputs and samples: the vector step gives
// continue_path's result bit for bit, dead paths included.
TEST(Lanes, LaneStepsAreContinuePathOnEverySimdTarget) {
    Estimator config;
    config.strategy = Strategy::Mis;
    config.rr_depth = 3;
    config.max_depth = 16;
    Scene scene;  // continue_path reads nothing of it on this path
    const LightSet lights;
    const size_t n = 53;
    struct Case {
        Vertex v;
        Vec3 wo;
        Color beta;
        ContinuationSamples u;
        float u_rr;
        int bounce;
    };
    std::vector<Case> cases;
    for (uint32_t i = 0; i < n; ++i) {
        auto u = [&](uint32_t d) { return sample_1d(9, i, 0, d); };
        Case c;
        c.v = lane_vertex_at(Vec3{u(0) - 0.5f, u(1) - 0.5f, u(2) - 0.5f} * 100.0f, u,
                             lane_kind(i, n, true));
        c.wo = unit(u(10), u(11));
        c.beta = Color(2.0f * u(12));
        c.u = {u(13), u(14), u(15), u(16), u(17), u(18), u(19)};
        c.u_rr = u(20);
        c.bounce = static_cast<int>(i % 5);
        cases.push_back(c);
    }
    size_t alive = 0, dead = 0, transmitted = 0, delta = 0;
    for (int64_t target : wide_simd_targets()) {
        use_wide_simd_target(target);
        SCOPED_TRACE(wide_simd_target());
        VertexBlock block;
        for (size_t k = 0; k < n; ++k) {
            const Case& c = cases[k];
            ASSERT_TRUE(takes_lane_step(config, c.v, lights));
            const size_t row = block.push(k, c.v, c.wo, c.beta);
            block.set_step(row, c.u, c.u_rr, c.bounce + 1 >= config.rr_depth);
        }
        step_vertices(block);
        for (size_t k = 0; k < n; ++k) {
            const Case& c = cases[k];
            MediumStack media;
            const PathStep one = continue_path(scene, lights, config, c.v, c.wo, PreviousVertex{}, c.bounce, c.beta, 1.0f,
                                               media, c.u, c.u_rr);
            ASSERT_EQ(one.alive, block.alive[k] != 0) << "row " << k;
            if (!one.alive) {
                ++dead;
                continue;
            }
            ++alive;
            EXPECT_TRUE(same_bits(one.next.o, block_row(block.origin, k))) << "row " << k;
            EXPECT_TRUE(same_bits(one.next.d, block_row(block.wi, k))) << "row " << k;
            EXPECT_TRUE(same_bits(one.weight, block_row(block.weight, k))) << "row " << k;
            EXPECT_TRUE(same_bits(one.prev.pdf_bsdf, block.pdf[k])) << "row " << k;
            EXPECT_TRUE(same_bits(one.eta_scale, block.next_eta_scale[k])) << "row " << k;
            EXPECT_EQ(c.v.bsdf.is_delta(), block.delta[k] != 0) << "row " << k;
            transmitted += block.transmitted[k] != 0;
            delta += block.delta[k] != 0;
        }
    }
    use_wide_simd_target(0);
    EXPECT_GT(alive, 0u);
    EXPECT_GT(dead, 0u);  // the geometric-side test and roulette were exercised
    EXPECT_GT(transmitted, 0u);  // refractions, which scale the eta scale
    EXPECT_GT(delta, 0u);
}

// Around two quad lights (one one-sided, one two-sided, of different power).
TEST(Lanes, QuadLightSamplesAreNextEventOnEverySimdTarget) {
    Scene scene;
    const auto [a, b] = add_emitters(scene);
    scene.add_quad({{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, a, kNone});  // faces -y
    scene.add_quad({{3, -1, -1}, {0, 2, 0}, {0, 0, 3}, b, kNone});
    size_t spheres;
    expect_light_samples_are_next_event(scene, &spheres);
    EXPECT_EQ(spheres, 0u);  // every row's light is a quad
}

// Around two triangle lights of a mesh (one-sided) and of another (two-sided) beside a quad
// light, so that vectors mix both shapes.
TEST(Lanes, TriangleLightSamplesAreNextEventOnEverySimdTarget) {
    Scene scene;
    const auto [a, b] = add_emitters(scene);
    Mesh one_sided, two_sided;
    one_sided.material = a;
    two_sided.material = b;
    ASSERT_EQ(scene.add_mesh(one_sided, {{-1, 2, -1}, {1, 2, -1}, {0, 2.5f, 1.5f}}, {}, {},
                             {0, 1, 2}),
              0u);
    ASSERT_EQ(scene.add_mesh(two_sided, {{3, -1, -1}, {3, 1, -1}, {3.5f, 0, 2}}, {}, {}, {0, 1, 2}),
              0u);
    scene.add_quad({{-1, -4, -1}, {2, 0, 0}, {0, 0, 2}, a, kNone});
    size_t spheres;
    expect_light_samples_are_next_event(scene, &spheres);
    EXPECT_EQ(spheres, 0u);  // every row's light is planar
}

// Around two sphere lights (one one-sided, one two-sided) and a quad light, so that vectors mix
// both kinds.
TEST(Lanes, SphereLightSamplesAreNextEventOnEverySimdTarget) {
    Scene scene;
    const auto [a, b] = add_emitters(scene);
    scene.add_sphere({{0, 4, 0}, 0.7f, a, kNone});
    scene.add_sphere({{5, 0, 1}, 1.5f, b, kNone});
    scene.add_quad({{-1, -4, -1}, {2, 0, 0}, {0, 0, 2}, a, kNone});
    size_t spheres;
    expect_light_samples_are_next_event(scene, &spheres);
    EXPECT_GT(spheres, 0u);
}

// Around a point and a directional light beside a quad light, so that vectors mix the kinds
// (and the two delta lights, which are MIS-weighted 1: a BSDF density of 0).
TEST(Lanes, DeltaLightSamplesAreNextEventOnEverySimdTarget) {
    Scene scene;
    const auto [a, b] = add_emitters(scene);
    scene.add_quad({{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, a, kNone});
    scene.lights.push_back(Light::point({0.5f, -3.0f, 1.0f}, Color(40.0f, 30.0f, 20.0f)));
    Light sun;
    sun.kind = Light::Kind::Directional;
    sun.direction = normalize(Vec3(0.3f, -1.0f, -0.4f));
    sun.intensity = Color(2.0f, 2.5f, 3.0f);
    scene.lights.push_back(sun);
    size_t spheres, deltas;
    expect_light_samples_are_next_event(scene, &spheres, nullptr, &deltas);
    EXPECT_GT(deltas, 10u);
}

// Under an environment map of either mapping, with a quad light beside it, so that vectors
// mix both kinds.
TEST(Lanes, EnvironmentLightSamplesAreNextEventOnEverySimdTarget) {
    for (const bool equal_area : {false, true}) {
        SCOPED_TRACE(equal_area ? "equal-area" : "lat-long");
        Scene scene;
        const auto [a, b] = add_emitters(scene);
        scene.add_quad({{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, a, kNone});
        add_environment(scene, 24, equal_area ? 24 : 12, equal_area);
        size_t spheres, maps;
        expect_light_samples_are_next_event(scene, &spheres, &maps);
        EXPECT_GT(maps, 0u);
    }
}

// The directions on the map that vertices of other BSDFs take in lanes: LightSet::sample's
// direction, radiance and density, bit for bit.
TEST(Lanes, EnvironmentLightPointsAreLightSetSamplesOnEverySimdTarget) {
    for (const bool equal_area : {false, true}) {
        SCOPED_TRACE(equal_area ? "equal-area" : "lat-long");
        Scene scene;
        add_environment(scene, 24, equal_area ? 24 : 12, equal_area);
        const LightSet lights(scene);
        const LightChoice map = lights.select(0.5f, Point3{0.0f}, Normal3{0.0f});
        ASSERT_TRUE(lights.is_environment(map));
        const size_t n = 53;
        for (int64_t target : wide_simd_targets()) {
            use_wide_simd_target(target);
            SCOPED_TRACE(wide_simd_target());
            EnvironmentPointBlock b;
            b.n = n;
            for (size_t k = 0; k < n; ++k) {
                b.u1[k] = sample_1d(19, uint32_t(k), 0, 0);
                b.u2[k] = sample_1d(19, uint32_t(k), 0, 1);
                b.select_prob[k] = map.probability;
            }
            environment_light_points(b, lights);
            for (size_t k = 0; k < n; ++k) {
                const LightSample ls = lights.sample(scene, {0, 0, 0}, map, b.u1[k], b.u2[k]);
                const LightSample lanes_ls = environment_light_sample(
                    block_row(b.wi, k), block_row(b.radiance, k), b.pdf[k]);
                ASSERT_TRUE(ls.valid) << "row " << k;
                EXPECT_TRUE(lanes_ls.valid) << "row " << k;
                EXPECT_TRUE(same_bits(ls.wi, lanes_ls.wi)) << "row " << k;
                EXPECT_TRUE(same_bits(ls.radiance, lanes_ls.radiance)) << "row " << k;
                EXPECT_TRUE(same_bits(ls.pdf, lanes_ls.pdf)) << "row " << k;
            }
        }
        use_wide_simd_target(0);
    }
}

// Rays leaving the scene in every direction, of several lengths: the vector lookups find
// resolve_segment's radiance and MIS density bit for bit.
TEST(Lanes, EscapedRaysAreResolveSegmentsOnEverySimdTarget) {
    for (const bool equal_area : {false, true}) {
        SCOPED_TRACE(equal_area ? "equal-area" : "lat-long");
        Scene scene;
        add_environment(scene, 24, equal_area ? 24 : 12, equal_area);
        const LightSet lights(scene);
        Estimator config;
        config.strategy = Strategy::Mis;
        const size_t n = 61;
        std::vector<Ray> rays;
        for (uint32_t i = 0; i < n; ++i) {
            auto u = [&](uint32_t d) { return sample_1d(17, i, 0, d); };
            Vec3 d = unit(u(0), u(1)) * (0.25f + 4.0f * u(2));
            if (i == 0) d = {3, 0, 0};  // the map's pole: its frame's t is the world's +x
            rays.push_back(Ray{{u(3), u(4), u(5)}, d});
        }
        for (int64_t target : wide_simd_targets()) {
            use_wide_simd_target(target);
            SCOPED_TRACE(wide_simd_target());
            EscapeBlock b;
            b.n = n;
            const PreviousVertex prev{{0, 0, 0}, 0.5f, false};
            for (size_t k = 0; k < n; ++k) {
                for (int a = 0; a < 3; ++a) b.dir[a][k] = rays[k].d[a];
                b.select_prob[k] = lights.background_selection_probability(prev.p, prev.n);
            }
            escape_rays(b, lights, true);
            for (size_t k = 0; k < n; ++k) {
                MediumStack media;
                float flight = 0.0f;
                const SegmentResult seg =
                    resolve_segment(scene, lights, config, rays[k], Hit{}, media, flight, prev);
                ASSERT_EQ(seg.event, SegmentEvent::Emission) << "row " << k;
                EXPECT_TRUE(same_bits(seg.emission, block_row(b.radiance, k))) << "row " << k;
                EXPECT_TRUE(same_bits(seg.emission_pdf_light, b.pdf_light[k])) << "row " << k;
                if (k > 0 || equal_area) {  // row 0 is a lat-long map's pole
                    EXPECT_GT(b.pdf_light[k], 0.0f) << "row " << k;
                }
            }
        }
        use_wide_simd_target(0);
    }
}

// Segments through media of two densities and none, hits and misses: the vector free flights
// scatter where scatters_in_medium says, at its distance, and leave it the same optical depth.
TEST(Lanes, MediumSegmentsAreScattersInMediumOnEverySimdTarget) {
    Scene scene;
    Material phase;
    phase.kind = MaterialKind::Isotropic;
    phase.albedo = scene.add_solid({0.5f, 0.5f, 0.5f});
    const MaterialId phase_id = scene.add_material(phase);
    scene.media.push_back({"thick", Color(0.3f), phase_id});
    scene.media.push_back({"thin", Color(0.01f), phase_id});
    const size_t n = 59;
    struct Case {
        Ray ray;
        Hit hit;
        MediumId medium;
        float flight;
    };
    std::vector<Case> cases;
    for (uint32_t i = 0; i < n; ++i) {
        auto u = [&](uint32_t d) { return sample_1d(21, i, 0, d); };
        Case c;
        c.ray = Ray{{u(0), u(1), u(2)}, unit(u(3), u(4)) * (0.5f + 2.0f * u(5))};
        if (i % 4 != 3) c.hit = Hit{20.0f * u(6), PrimRef::make(PrimKind::Quad, i), 0.0f, 0.0f};
        c.medium = i % 3 == 2 ? kNone : MediumId(i % 3);
        c.flight = sample_free_flight(1.0f, u(7));
        cases.push_back(c);
    }
    size_t scattered = 0, through = 0;
    for (int64_t target : wide_simd_targets()) {
        use_wide_simd_target(target);
        SCOPED_TRACE(wide_simd_target());
        MediumSegmentBlock b;
        for (size_t k = 0; k < n; ++k) {
            const Case& c = cases[k];
            for (int a = 0; a < 3; ++a) b.dir[a][k] = c.ray.d[a];
            b.t[k] = c.hit.found() ? c.hit.t : kInfinity;
            b.medium[k] = c.medium != kNone ? 1.0f : 0.0f;
            b.density[k] = c.medium != kNone ? scene.media[c.medium].sigma_t.x : 0.0f;
            b.flight[k] = c.flight;
        }
        medium_segments(b, n);
        for (size_t k = 0; k < n; ++k) {
            const Case& c = cases[k];
            const float dir_length = length(c.ray.d);
            float flight = c.flight, dist = 0.0f;
            Color weight;
            const bool scatters = scatters_in_medium(scene, c.medium, c.ray, c.hit, dir_length,
                                                     flight, &dist, &weight);
            ASSERT_EQ(weight, Color(1.0f)) << "grey media need no weight";
            ASSERT_TRUE(same_bits(b.dir_length[k], dir_length)) << "row " << k;
            ASSERT_EQ(b.scatters[k] != 0.0f, scatters) << "row " << k;
            if (scatters) {
                ASSERT_TRUE(same_bits(b.dist[k], dist)) << "row " << k;
                ++scattered;
            } else {
                ASSERT_TRUE(same_bits(b.flight[k], flight)) << "row " << k;
                ++through;
            }
        }
    }
    use_wide_simd_target(0);
    EXPECT_GT(scattered, 0u);
    EXPECT_GT(through, 0u);
}

// The free flights' logarithm (Log1p, one formula in every lane and in scalar code) against the
// C library's: within 2 ulp-sized relative errors over [-1 + 2^-24, 1], exact near 0, and the
// optical depth of u -> 1 finite and large.
TEST(Lanes, Log1pIsTheLibraryOne) {
    float worst = 0.0f;
    for (uint32_t i = 0; i < 200000; ++i) {
        const float u = sample_1d(11, i, 0, 0);
        for (float x : {-u, u, -u * 1e-3f, u * 1e-6f, -u * 1e-9f}) {
            const double exact = std::log1p(double(x));
            const float ours = lanes::Log1p<OneLane>(x);
            if (exact != 0.0) worst = std::max(worst, float(std::fabs((ours - exact) / exact)));
        }
    }
    EXPECT_LT(worst, 3e-7f);
    std::printf("Log1p: worst relative error %.3g\n", worst);
    EXPECT_EQ(lanes::Log1p<OneLane>(0.0f), 0.0f);
    EXPECT_EQ(lanes::Log1p<OneLane>(1e-30f), 1e-30f);
    const float last = std::nextafter(1.0f, 0.0f);  // the largest u < 1
    EXPECT_NEAR(sample_free_flight(1.0f, last), 24.0f * std::log(2.0f), 1e-4f);
    EXPECT_EQ(sample_free_flight(2.0f, 0.0f), 0.0f);
}

// The exponential (Beckmann's density, Lambda and visible normals) against the C library's in
// double: within 2 ulp-sized relative errors from 2^-126 to e^88, 0 below; and the complementary
// error function's Gaussian factor, erfc(a) = ErfcOverGaussian(a) e^(-a^2), within A&S 7.1.26's
// absolute 1.5e-7 plus the rounding of its alternating sum in float (about 4 ulp of 1 near 0).
TEST(Lanes, ExpAndErfcAreTheLibraryOnes) {
    double worst_exp = 0, worst_erfc = 0;
    for (int i = 0; i <= 1 << 16; ++i) {
        const float x = -87.0f + 175.0f * float(i) / float(1 << 16);
        const double exact = std::exp(double(x));
        worst_exp = std::max(worst_exp, std::fabs(lanes::Exp<OneLane>(x) - exact) / exact);
        const float a = 10.0f * float(i) / float(1 << 16);
        const double ours = double(lanes::ErfcOverGaussian<OneLane>(a)) * std::exp(-double(a) * a);
        worst_erfc = std::max(worst_erfc, std::fabs(ours - std::erfc(double(a))));
    }
    std::printf("Exp: worst relative error %.3g; erfc: worst absolute error %.3g\n", worst_exp,
                worst_erfc);
    EXPECT_LT(worst_exp, 2.4e-7);
    EXPECT_LT(worst_erfc, 6e-7);
    EXPECT_EQ(lanes::Exp<OneLane>(0.0f), 1.0f);
    EXPECT_EQ(lanes::Exp<OneLane>(-90.0f), 0.0f);
    EXPECT_EQ(lanes::Exp<OneLane>(-kInfinity), 0.0f);
}

// Filter importance sampling: the offsets of evenly spaced u are the filters' quantiles, F(x(u))
// = u, for the tent's closed form and the truncated Gaussian's inverse error function.
TEST(Lanes, PixelFilterOffsetsInvertTheFiltersDistributions) {
    const int n = 20000;
    for (float r : {1.0f, 2.0f}) {
        float worst = 0, last = -r;
        for (int i = 0; i < n; ++i) {
            const double u = (i + 0.5) / n;
            const float x = lanes::TentOffset<OneLane>(static_cast<float>(u), r);
            const double cdf = x < 0 ? (x + r) * (x + r) / (2.0 * r * r)
                                     : 1 - (r - x) * (r - x) / (2.0 * r * r);
            worst = std::max(worst, float(std::fabs(cdf - u)));
            EXPECT_GE(x, last);
            last = x;
        }
        EXPECT_LT(worst, 2e-6f) << "tent " << r;
        EXPECT_LE(last, r);
    }
    for (auto [sigma, r] : {std::pair{0.5f, 2.0f}, {0.5f, 1.5f}, {1.0f, 1.0f}}) {
        const double e = std::erf(r / (sigma * std::sqrt(2.0)));
        float worst = 0, last = -r;
        for (int i = 0; i < n; ++i) {
            const double u = (i + 0.5) / n;
            const float x = lanes::GaussianOffset<OneLane>(static_cast<float>(u), sigma, float(e));
            const double cdf = (std::erf(x / (sigma * std::sqrt(2.0))) + e) / (2 * e);
            worst = std::max(worst, float(std::fabs(cdf - u)));
            EXPECT_GE(x, last);
            last = x;
        }
        EXPECT_LT(worst, 1e-5f) << "gaussian " << sigma << " " << r;
        EXPECT_LE(last, r * 1.0001f);
    }
}

TEST(Lanes, MisWeightKeepsItsGuards) {
    for (MisHeuristic h : {MisHeuristic::Power, MisHeuristic::Balance}) {
        EXPECT_EQ(mis_weight(h, kInfinity, kInfinity), 1.0f);
        EXPECT_EQ(mis_weight(h, 1.0f, kInfinity), 0.0f);
        EXPECT_EQ(mis_weight(h, 0.0f, 0.0f), 0.0f);
        EXPECT_EQ(mis_weight(h, 2.0f, 0.0f), 1.0f);
        EXPECT_EQ(mis_weight(h, std::nanf(""), 1.0f), 0.0f);
        EXPECT_EQ(mis_weight(h, 1.0f, 1.0f), 0.5f);
    }
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Power, 1.0f, 2.0f), 0.2f);
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Balance, 1.0f, 3.0f), 0.25f);
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Power, 1e30f, 1e29f), 1.0f / 1.01f);  // no overflow
}

// Camera rays of a pinhole and of a thin-lens camera: the vector ones are generate_camera_ray's.
// mis_combine's weights of a queue's shadow rays, a vector at a time: direct_weight's, bit for
// bit, for every strategy and pair of heuristics (the second for rays of infinite length),
// guards included (zero and infinite densities), over lengths that end in a partial vector.
TEST(Lanes, DirectWeightsAreDirectWeightOnEverySimdTarget) {
    const size_t n = 61;
    std::vector<float> pl(n), pb(n), tmax(n), w(n);
    for (uint32_t i = 0; i < n; ++i) {
        pl[i] = i % 11 == 0 ? 0.0f : i % 13 == 0 ? kInfinity : 10.0f * sample_1d(4, i, 0, 0);
        pb[i] = i % 7 == 0 ? 0.0f : i % 17 == 0 ? kInfinity : 10.0f * sample_1d(4, i, 0, 1);
        tmax[i] = i % 3 == 0 ? kInfinity : 1.0f + float(i);
    }
    const MisHeuristic heuristics[] = {MisHeuristic::Power, MisHeuristic::Balance};
    for (int64_t target : wide_simd_targets()) {
        use_wide_simd_target(target);
        SCOPED_TRACE(wide_simd_target());
        for (Strategy st :
             {Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Nee, Strategy::Mis})
            for (MisHeuristic h : heuristics)
                for (MisHeuristic at_infinity : heuristics)
                    for (size_t m : {n, size_t(3), size_t(0)}) {
                        std::fill(w.begin(), w.end(), -1.0f);
                        direct_weights(st, h, at_infinity, pl.data(), pb.data(), tmax.data(), m,
                                       w.data());
                        for (size_t k = 0; k < n; ++k) {
                            const MisHeuristic hk = std::isinf(tmax[k]) ? at_infinity : h;
                            ASSERT_TRUE(same_bits(
                                w[k], k < m ? direct_weight(st, hk, pl[k], pb[k]) : -1.0f))
                                << to_string(st) << " row " << k << " of " << m;
                        }
                    }
    }
    use_wide_simd_target(0);
}

TEST(Lanes, CameraRaysAreTheScalarOnesOnEverySimdTarget) {
    for (float aperture : {0.0f, 0.5f}) {
        Camera camera;
        camera.look_from = {1, 2, 3};
        camera.look_at = {0, 0.5f, -1};
        camera.aperture = aperture;
        const CameraRays rays(camera, 37, 23);
        const size_t n = 45;
        uint32_t pixel[kShadeChunk], sample[kShadeChunk];
        float x[kShadeChunk], y[kShadeChunk];
        for (size_t k = 0; k < n; ++k) {
            pixel[k] = static_cast<uint32_t>(k * 19 % (37 * 23));
            sample[k] = static_cast<uint32_t>(1 + k % 6);  // across ZSobol's blocks of 4
            x[k] = static_cast<float>(pixel[k] % 37);
            y[k] = static_cast<float>(pixel[k] / 37);
        }
        for (int64_t target : wide_simd_targets()) {
            use_wide_simd_target(target);
            for (SamplerKind kind :
                 {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol}) {
                SCOPED_TRACE(std::string(wide_simd_target()) + " aperture " +
                             std::to_string(aperture) + " " + to_string(kind));
                const Sampler sampler{5, kind, 37, 23, 2};
                CameraRayBlock block;
                draw_camera_rays(rays, sampler, sample, pixel, x, y, n, true, block);
                for (size_t k = 0; k < n; ++k) {
                    const Ray one = generate_camera_ray(rays, sampler, pixel[k], sample[k],
                                                        int(x[k]), int(y[k]));
                    EXPECT_TRUE(same_bits(one.o, {block.o[0][k], block.o[1][k], block.o[2][k]}))
                        << "row " << k;
                    EXPECT_TRUE(same_bits(one.d, {block.d[0][k], block.d[1][k], block.d[2][k]}))
                        << "row " << k;
                    const float u =
                        sample_1d(sampler, pixel[k], sample[k], bounce_dim(0, kDimMediumDistance));
                    EXPECT_TRUE(same_bits(block.flight[k], sample_free_flight(1.0f, u)))
                        << "row " << k;
                }
            }
        }
    }
    use_wide_simd_target(0);
}

// Hits on random quads and on triangles of meshes with and without vertex normals (some flipped
// against the face, so that the shading normal is turned over): the rows the block resolves from
// the hit get surface_at's point and normals and resolve_segment's wo, and the same light-free
// continuation as rows given that vertex, bit for bit.
TEST(Lanes, HitsResolvedInLanesAreSurfaceAtOnEverySimdTarget) {
    Scene scene;
    const MaterialId white = scene.add_material({});
    std::vector<Point3> positions;
    std::vector<Normal3> normals;
    std::vector<uint32_t> indices;
    const uint32_t triangles = 24;
    for (uint32_t i = 0; i < triangles; ++i) {
        auto u = [&](uint32_t d) { return sample_1d(5, i, 0, d); };
        const Point3 o{u(0) * 20.0f - 10.0f, u(1) * 20.0f - 10.0f, u(2) * 20.0f - 10.0f};
        for (int k = 0; k < 3; ++k) {
            positions.push_back(o + 3.0f * unit(u(3 + 2 * k), u(4 + 2 * k)));
            normals.push_back(unit(u(9 + 2 * k), u(10 + 2 * k)));
            indices.push_back(3 * i + k);
        }
    }
    Mesh smooth, flat;
    smooth.material = flat.material = white;
    ASSERT_EQ(scene.add_mesh(smooth, positions, normals, {}, indices), 0u);
    ASSERT_EQ(scene.add_mesh(flat, positions, {}, {}, indices), 0u);
    for (uint32_t i = 0; i < 8; ++i) {
        auto u = [&](uint32_t d) { return sample_1d(6, i, 0, d); };
        scene.add_quad({{u(0) * 10.0f, u(1) * 10.0f, u(2) * 10.0f},
                        4.0f * unit(u(3), u(4)),
                        (1.0f + u(5)) * unit(u(6), u(7)),
                        white});
    }
    const size_t prims = 2 * triangles + scene.quads.size();

    Estimator config;
    config.strategy = Strategy::Mis;
    const LightSet lights;
    const size_t n = 59;  // rows: hits, then the same vertices given
    struct Case {
        Ray ray;
        Hit hit;
        BsdfParams bsdf;
        Color beta;
        ContinuationSamples u;
        float u_rr;
    };
    std::vector<Case> cases;
    for (uint32_t i = 0; i < n; ++i) {
        auto u = [&](uint32_t d) { return sample_1d(7, i, 0, d); };
        const size_t k = i % prims;
        const PrimRef prim = k < 2 * triangles
                                 ? PrimRef::make(PrimKind::Triangle, uint32_t(k))
                                 : PrimRef::make(PrimKind::Quad, uint32_t(k - 2 * triangles));
        float a = u(0), b = u(1);
        if (prim.kind() == PrimKind::Triangle && a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
        Case c;
        c.ray = Ray{{u(2) * 30.0f, u(3) * 30.0f, u(4) * 30.0f}, unit(u(5), u(6)) * (0.5f + u(7))};
        c.hit = Hit{1.0f + u(8), prim, a, b};
        c.bsdf.albedo = {u(9), u(10), u(11)};
        if (3 * i >= n) {  // rough metal, then rough conductor, dielectric, metallic-roughness
            c.bsdf.kind = 3 * i < 2 * n ? MaterialKind::Metal
                          : i % 3 == 0  ? MaterialKind::Conductor
                          : i % 3 == 1  ? MaterialKind::Dielectric
                                        : MaterialKind::MetallicRoughness;
            c.bsdf.eta = 1.5f;
            c.bsdf.metallic = u(29);
            c.bsdf.clearcoat = u(30) < 0.5f ? 0.0f : 1.0f;
            c.bsdf.clearcoat_alpha = 0.1f;
            c.bsdf.transmission = u(31) < 0.5f ? 0.0f : 1.0f;
            c.bsdf.alpha = c.bsdf.alpha_v = 0.02f + 0.6f * u(21);
            c.bsdf.conductor_eta = {0.2f + u(22), 0.2f + u(23), 0.2f + u(24)};
            c.bsdf.conductor_k = {3.0f * u(25), 3.0f * u(26), 3.0f * u(27)};
            c.bsdf.distribution = u(28) < 0.5f ? Microfacet::Beckmann : Microfacet::Ggx;
        }
        c.beta = Color(2.0f * u(12));
        c.u = {u(13), u(14), u(15), u(16), u(17), u(18), u(19)};
        c.u_rr = u(20);
        cases.push_back(c);
    }
    size_t flipped = 0;
    for (int64_t target : wide_simd_targets()) {
        use_wide_simd_target(target);
        SCOPED_TRACE(wide_simd_target());
        VertexBlock hits, given;
        for (size_t k = 0; k < n; ++k) {
            const Case& c = cases[k];
            const uint32_t index = c.hit.prim.index();
            size_t r;
            if (c.hit.prim.kind() == PrimKind::Quad) {
                r = hits.push_quad_hit(k, c.ray.d, c.hit.u, c.hit.v, scene.quads[index], white,
                                       c.bsdf, c.beta);
            } else {
                const Triangle& t = scene.triangles[index];
                const Point3 p[3] = {scene.positions[t.v[0]], scene.positions[t.v[1]],
                                     scene.positions[t.v[2]]};
                const Normal3 nv[3] = {scene.normals[t.v[0]], scene.normals[t.v[1]],
                                       scene.normals[t.v[2]]};
                r = hits.push_triangle_hit(k, c.ray.d, c.hit.u, c.hit.v, p,
                                           scene.meshes[t.mesh].has_normals ? nv : nullptr, white,
                                           c.bsdf, c.beta);
            }
            hits.set_step(r, c.u, c.u_rr, true);
            // The scalar path: surface_at, and resolve_segment's wo = -d / |d|.
            const SurfaceHit s = surface_at(scene, c.ray, c.hit);
            const Vec3 wo = -(c.ray.d / length(c.ray.d));
            Vertex v = surface_vertex(scene, s, wo);
            v.bsdf = c.bsdf;
            given.set_step(given.push(k, v, wo, c.beta), c.u, c.u_rr, true);
            if (c.hit.prim.kind() == PrimKind::Triangle &&
                scene.meshes[scene.triangles[index].mesh].has_normals) {
                const Triangle& t = scene.triangles[index];
                const float b0 = 1.0f - c.hit.u - c.hit.v;
                const Vec3 ni = b0 * scene.normals[t.v[0]] + c.hit.u * scene.normals[t.v[1]] +
                                c.hit.v * scene.normals[t.v[2]];
                flipped += dot(ni, s.ng) < 0.0f;
            }
        }
        resolve_surface_hits(hits);
        resolve_surface_hits(given);  // nothing to resolve: the rows stay as given
        step_vertices(hits);
        step_vertices(given);
        for (size_t k = 0; k < n; ++k) {
            for (auto rows :
                 {&VertexBlock::p, &VertexBlock::ng, &VertexBlock::ns, &VertexBlock::wo})
                ASSERT_TRUE(same_bits(block_row(hits.*rows, k), block_row(given.*rows, k)))
                    << "row " << k;
            ASSERT_EQ(hits.alive[k], given.alive[k]) << "row " << k;
            if (given.alive[k] == 0) continue;
            for (auto rows : {&VertexBlock::origin, &VertexBlock::wi, &VertexBlock::weight})
                ASSERT_TRUE(same_bits(block_row(hits.*rows, k), block_row(given.*rows, k)))
                    << "row " << k;
            ASSERT_TRUE(same_bits(hits.pdf[k], given.pdf[k])) << "row " << k;
        }
    }
    use_wide_simd_target(0);
    EXPECT_GT(flipped, 0u);  // interpolated normals that disagree with the face were exercised
}

// The guided search of a Distribution2D's sums finds the entry a search of all of them finds
// (the last i with sums[i] <= u total), for rows of even, peaked, zero-padded and random weights,
// and for u at the guide's cutpoints, next to them, at 0 and just below 1.
TEST(Lanes, GuidedSearchFindsTheEntryOfTheFullSearch) {
    const int nu = 37, nv = 9;
    std::vector<float> weights(size_t(nu) * nv);
    for (int v = 0; v < nv; ++v)
        for (int u = 0; u < nu; ++u) {
            const float r = sample_1d(23, uint32_t(v * nu + u), 0, 0);
            float& w = weights[size_t(v) * nu + u];
            switch (v % 4) {
                case 0:
                    w = 1.0f;
                    break;  // even
                case 1:
                    w = u == 17 ? 1e6f : 1e-3f;
                    break;  // one peak
                case 2:
                    w = u < 30 ? 0.0f : r;
                    break;  // zeros, then weights
                default:
                    w = r * r * r * 100.0f;
                    break;  // random
            }
        }
    const Distribution2D dist(weights, nu, nv);
    const Distribution2DTables t = dist.tables();
    auto check = [&](const float* sums, int n, const int32_t* guide, int g) {
        std::vector<float> us = {0.0f, 0x1.fffffep-1f};
        for (int j = 0; j <= g; ++j) {
            const float c = float(j) / float(g);
            us.push_back(c);
            us.push_back(std::nextafter(c, 0.0f));
            if (j < g) us.push_back(std::nextafter(c, 1.0f));
        }
        for (uint32_t k = 0; k < 2000; ++k) us.push_back(sample_1d(29, k, 0, 0));
        for (float u : us) {
            if (!(u >= 0.0f && u < 1.0f)) continue;
            const float target = u * sums[n];
            int want = 0;
            for (int i = 1; i < n; ++i)
                if (sums[i] <= target) want = i;
            float x;
            int32_t index;
            lanes::SampleSums<OneLane>(sums, 0, n, guide, 0, g, u, &x, &index);
            ASSERT_EQ(index, want) << "u " << u;
        }
    };
    check(t.marginal, nv, t.marginal_guide, t.gv);
    for (int v = 0; v < nv; ++v) {
        SCOPED_TRACE(v);
        check(t.conditional + size_t(v) * (nu + 1), nu,
              t.conditional_guide + size_t(v) * (t.gu + 1), t.gu);
    }
}
