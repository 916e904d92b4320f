// Each primitive's intersection: hit, miss, from inside, grazing; and watertightness.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "accel/intersect.h"
#include "sampling/sampler.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

TEST(Sphere, HitFromOutsideGivesNearRoot) {
    PrimHit h;
    ASSERT_TRUE(intersect_sphere({{0, 0, -5}, {0, 0, 1}}, {0, 0, 0}, 1, &h));
    EXPECT_FLOAT_EQ(h.t, 4.0f);
    // A non-unit direction scales t.
    ASSERT_TRUE(intersect_sphere({{0, 0, -5}, {0, 0, 2}}, {0, 0, 0}, 1, &h));
    EXPECT_FLOAT_EQ(h.t, 2.0f);
}

TEST(Sphere, Miss) {
    PrimHit h;
    EXPECT_FALSE(intersect_sphere({{0, 1.01f, -5}, {0, 0, 1}}, {0, 0, 0}, 1, &h));
    EXPECT_FALSE(intersect_sphere({{0, 0, -5}, {0, 0, -1}}, {0, 0, 0}, 1, &h));          // behind
    EXPECT_FALSE(intersect_sphere({{0, 0, -5}, {0, 0, 1}, 0, 3.9f}, {0, 0, 0}, 1, &h));  // tmax
}

TEST(Sphere, FromInsideHitsFarSide) {
    PrimHit h;
    ASSERT_TRUE(intersect_sphere({{0, 0, 0.5f}, {0, 0, 1}}, {0, 0, 0}, 1, &h));
    EXPECT_FLOAT_EQ(h.t, 0.5f);
    // The huge fog sphere of `everything`, seen from inside near its centre.
    ASSERT_TRUE(intersect_sphere({{478, 278, -600}, {0, 0, 1}}, {0, 0, 0}, 5000, &h));
    EXPECT_NEAR(h.t - 600, std::sqrt(5000.0f * 5000 - 478 * 478 - 278 * 278), 0.05f);
}

TEST(Sphere, GrazingTangentRay) {
    PrimHit h;
    // Tangent at (0, 1, 0): a double root, still a hit; a hair above misses.
    ASSERT_TRUE(intersect_sphere({{-5, 1, 0}, {1, 0, 0}}, {0, 0, 0}, 1, &h));
    EXPECT_NEAR(h.t, 5.0f, 1e-3f);
    EXPECT_FALSE(intersect_sphere({{-5, 1.0001f, 0}, {1, 0, 0}}, {0, 0, 0}, 1, &h));
}

TEST(Sphere, FarAwayRayIsPrecise) {
    // Classic cancellation case: small sphere far from the origin of the ray.
    PrimHit h;
    ASSERT_TRUE(intersect_sphere({{0, 0, -1e4f}, {0, 0, 1}}, {0, 0, 0}, 0.01f, &h));
    EXPECT_NEAR(h.t, 1e4f - 0.01f, 1e-3f);
}

TEST(Quad, HitInsideWithParameters) {
    PrimHit h;
    ASSERT_TRUE(
        intersect_quad({{0.25f, 0.75f, -1}, {0, 0, 1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    EXPECT_FLOAT_EQ(h.t, 1.0f);
    EXPECT_FLOAT_EQ(h.u, 0.25f);
    EXPECT_FLOAT_EQ(h.v, 0.75f);
    // From behind too: quads are two-sided for intersection.
    ASSERT_TRUE(intersect_quad({{0.5f, 0.5f, 2}, {0, 0, -1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    EXPECT_FLOAT_EQ(h.t, 2.0f);
}

TEST(Quad, MissOutsideParallelAndBehind) {
    PrimHit h;
    EXPECT_FALSE(
        intersect_quad({{1.5f, 0.5f, -1}, {0, 0, 1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    EXPECT_FALSE(
        intersect_quad({{0.5f, 0.5f, -1}, {1, 0, 0}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    EXPECT_FALSE(
        intersect_quad({{0.5f, 0.5f, -1}, {0, 0, -1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
}

TEST(Quad, EdgesAreInclusive) {
    PrimHit h;
    EXPECT_TRUE(intersect_quad({{1, 0.5f, -1}, {0, 0, 1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    EXPECT_TRUE(intersect_quad({{0, 0, -1}, {0, 0, 1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
}

TEST(Quad, GrazingRayInItsPlaneMisses) {
    PrimHit h;
    EXPECT_FALSE(intersect_quad({{-1, 0.5f, 0}, {1, 0, 0}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
}

TEST(Triangle, HitGivesBarycentrics) {
    PrimHit h;
    ASSERT_TRUE(
        intersect_triangle({{0.2f, 0.3f, -1}, {0, 0, 1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    EXPECT_FLOAT_EQ(h.t, 1.0f);
    EXPECT_NEAR(h.u, 0.2f, 1e-6f);
    EXPECT_NEAR(h.v, 0.3f, 1e-6f);
}

TEST(Triangle, MissAndBackfaceAndInside) {
    PrimHit h;
    EXPECT_FALSE(
        intersect_triangle({{0.6f, 0.6f, -1}, {0, 0, 1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    // Both faces are hit (culling is the shading's business).
    EXPECT_TRUE(
        intersect_triangle({{0.2f, 0.2f, 1}, {0, 0, -1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    // A ray starting on the triangle does not hit it again.
    EXPECT_FALSE(
        intersect_triangle({{0.2f, 0.2f, 0}, {0, 0.3f, 1}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
    // Degenerate triangles are never hit.
    EXPECT_FALSE(
        intersect_triangle({{0.5f, 0, -1}, {0, 0, 1}}, {0, 0, 0}, {1, 0, 0}, {2, 0, 0}, &h));
}

TEST(Triangle, GrazingInPlaneMisses) {
    PrimHit h;
    EXPECT_FALSE(
        intersect_triangle({{-1, 0.2f, 0}, {1, 0, 0}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, &h));
}

namespace {

// A closed, consistently wound icosphere subdivided `levels` times, centred at c.
void add_icosphere(Scene& scene, Point3 c, float r, int levels) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<Point3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                             {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                             {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<uint32_t> f = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                               4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                               6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (int l = 0; l < levels; ++l) {
        std::vector<uint32_t> g;
        for (size_t i = 0; i < f.size(); i += 3) {
            uint32_t a = f[i], b = f[i + 1], cc = f[i + 2];
            auto mid = [&](uint32_t x, uint32_t y) {
                v.push_back(0.5f * (v[x] + v[y]));
                return static_cast<uint32_t>(v.size() - 1);
            };
            // Midpoints are recomputed per face but from the same two floats, so they are
            // bit-identical on both sides of an edge.
            uint32_t ab = mid(a, b), bc = mid(b, cc), ca = mid(cc, a);
            g.insert(g.end(), {a, ab, ca, b, bc, ab, cc, ca, bc, ab, bc, ca});
        }
        f = g;
    }
    for (Point3& p : v) p = c + r * normalize(p);
    Material m;
    scene.add_material(m);
    scene.add_mesh({}, v, {}, {}, f);
}

}  // namespace

// Rays from inside a closed mesh aimed exactly at its vertices and edge points must all hit:
// a leak through a shared edge would be a miss.
TEST(Triangle, ClosedMeshIsWatertight) {
    Scene scene;
    add_icosphere(scene, {0.3f, -0.2f, 0.1f}, 2.0f, 3);
    Bvh bvh = Bvh::build(scene);
    size_t rays = 0, leaks = 0;
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
        const Triangle& tri = scene.triangles[i];
        Point3 p[3] = {scene.positions[tri.v[0]], scene.positions[tri.v[1]],
                       scene.positions[tri.v[2]]};
        for (int k = 0; k < 3; ++k) {
            for (float s : {0.0f, 0.5f, 1.0f / 3.0f, 0.123f}) {
                Point3 target = lerp(s, p[k], p[(k + 1) % 3]);
                for (int o = 0; o < 4; ++o) {
                    Point3 origin{0.3f + 0.4f * sample_1d(1, i, k * 16 + o, 0) - 0.2f,
                                  -0.2f + 0.4f * sample_1d(1, i, k * 16 + o, 1) - 0.2f,
                                  0.1f + 0.4f * sample_1d(1, i, k * 16 + o, 2) - 0.2f};
                    Ray ray{origin, target - origin};
                    ++rays;
                    if (!bvh.occluded(ray) || !bvh.intersect(ray).found()) ++leaks;
                }
            }
        }
    }
    std::printf("watertight: %zu rays through edges and vertices of %zu triangles, %zu leaks\n",
                rays, scene.triangles.size(), leaks);
    EXPECT_EQ(leaks, 0u);
}
