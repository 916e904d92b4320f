#include <gtest/gtest.h>

#include "chi2.h"
#include "math/equal_area.h"
#include "sampling/sampler.h"
#include "wavetrace/math/aabb.h"
#include "wavetrace/math/frame.h"
#include "wavetrace/math/transform.h"

using namespace wavetrace;

namespace {
void expect_near(Vec3 a, Vec3 b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
}  // namespace

TEST(Transform, TranslateMovesPointsNotVectors) {
    Transform t = Transform::translate({1, 2, 3});
    expect_near(t.point({0, 0, 0}), {1, 2, 3});
    expect_near(t.vector({1, 0, 0}), {1, 0, 0});
}

TEST(Transform, RotateIsRightHanded) {
    // +90 degrees about +y takes +z to +x and +x to -z (rotate_y of Ray Tracing: The Next Week).
    Transform r = Transform::rotate({0, 1, 0}, 90);
    expect_near(r.vector({0, 0, 1}), {1, 0, 0});
    expect_near(r.vector({1, 0, 0}), {0, 0, -1});
    // About an arbitrary axis the axis itself is fixed and lengths are kept.
    Transform a = Transform::rotate({1, 1, 1}, 120);
    expect_near(a.vector({1, 1, 1}), {1, 1, 1});
    expect_near(a.vector({1, 0, 0}), {0, 1, 0});  // a third of a turn cycles the axes
}

TEST(Transform, ComposeAppliesRightOperandFirst) {
    Transform s = Transform::scale({2, 2, 2});
    Transform t = Transform::translate({1, 0, 0});
    expect_near((t * s).point({1, 0, 0}), {3, 0, 0});
    expect_near((s * t).point({1, 0, 0}), {4, 0, 0});
}

TEST(Transform, InverseUndoes) {
    Transform m = Transform::translate({3, -1, 2}) * Transform::rotate({0.3f, 1, -0.2f}, 37) *
                  Transform::scale({2, 0.5f, 3});
    Point3 p{0.7f, -1.2f, 4.0f};
    expect_near(m.inverse().point(m.point(p)), p, 1e-4f);
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
    Transform m = Transform::rotate({1, 2, 3}, 40) * Transform::scale({1, 4, 0.5f});
    Vec3 tangent{1, -1, 0}, n{1, 1, 0};  // perpendicular before
    EXPECT_NEAR(dot(m.vector(tangent), m.normal(n)), 0.0f, 1e-5f);
}

TEST(Transform, PreservesShapeDetectsUniformScale) {
    float s = 0;
    EXPECT_TRUE((Transform::rotate({0, 1, 0}, 30) * Transform::scale(Vec3(2))).preserves_shape(&s));
    EXPECT_NEAR(s, 2.0f, 1e-5f);
    EXPECT_FALSE(Transform::scale({1, 2, 1}).preserves_shape(&s));
}

TEST(Frame, IsOrthonormalForAnyNormal) {
    for (Vec3 n : {Vec3{0, 0, 1}, Vec3{0, 0, -1}, normalize(Vec3{1, 2, 3}),
                   normalize(Vec3{-1e-4f, 1, 0}), Vec3{1, 0, 0}}) {
        Frame f = Frame::from_normal(n);
        EXPECT_NEAR(dot(f.s, f.t), 0, 1e-6f);
        EXPECT_NEAR(dot(f.s, f.n), 0, 1e-6f);
        EXPECT_NEAR(dot(f.t, f.n), 0, 1e-6f);
        EXPECT_NEAR(length(f.s), 1, 1e-6f);
        EXPECT_NEAR(length(f.t), 1, 1e-6f);
        expect_near(f.to_world(f.to_local({0.3f, -0.5f, 0.8f})), {0.3f, -0.5f, 0.8f});
    }
}

TEST(Aabb, GrowAndContain) {
    Aabb b;
    EXPECT_TRUE(b.empty());
    b.grow(Vec3{1, 2, 3});
    b.grow(Vec3{-1, 0, 5});
    EXPECT_FALSE(b.empty());
    EXPECT_FLOAT_EQ(b.half_area(), 2 * 2 + 2 * 2 + 2 * 2);
    EXPECT_TRUE(b.contains(Aabb{{0, 1, 4}, {1, 2, 5}}));
    EXPECT_FALSE(b.contains(Aabb{{0, 1, 4}, {1, 2, 6}}));
}

// pbrt-v4's layout of the equal-area square: +z at the centre, -z at the corners, +x to the
// right (u = 1) and +y at v = 1; the mapping is a bijection on the open square and keeps areas.
TEST(EqualArea, LayoutIsPbrtV4s) {
    expect_near(equal_area_square_to_sphere(0.5f, 0.5f), {0, 0, 1});
    for (float u : {0.0f, 1.0f})
        for (float v : {0.0f, 1.0f}) expect_near(equal_area_square_to_sphere(u, v), {0, 0, -1});
    expect_near(equal_area_square_to_sphere(1.0f, 0.5f), {1, 0, 0});
    expect_near(equal_area_square_to_sphere(0.0f, 0.5f), {-1, 0, 0});
    expect_near(equal_area_square_to_sphere(0.5f, 1.0f), {0, 1, 0});
    expect_near(equal_area_square_to_sphere(0.5f, 0.0f), {0, -1, 0});
    // The inner diamond is the upper hemisphere.
    EXPECT_GT(equal_area_square_to_sphere(0.7f, 0.6f).z, 0.0f);
    EXPECT_LT(equal_area_square_to_sphere(0.9f, 0.8f).z, 0.0f);
}

TEST(EqualArea, SphereToSquareInvertsSquareToSphere) {
    for (int i = 1; i < 64; ++i)
        for (int j = 1; j < 64; ++j) {
            const float u = i / 64.0f + 0.001f, v = j / 64.0f - 0.002f;
            const Vec3 d = equal_area_square_to_sphere(u, v);
            EXPECT_NEAR(length(d), 1.0f, 1e-6f);
            const Vec2 back = equal_area_sphere_to_square(d);
            EXPECT_NEAR(back.x, u, 2e-6f) << u << " " << v;
            EXPECT_NEAR(back.y, v, 2e-6f) << u << " " << v;
        }
    // Near the poles, where 1 - |z| would lose its digits in float: within the resolution of
    // the square's coordinates there (2^-24 near its centre, 4e-7 of the sphere's 2).
    const Vec2 near_pole = equal_area_sphere_to_square(normalize(Vec3(1e-4f, 2e-4f, 1.0f)));
    expect_near(equal_area_square_to_sphere(near_pole.x, near_pole.y),
                normalize(Vec3(1e-4f, 2e-4f, 1.0f)), 4e-7f);
}

// Uniform points of the square land uniformly on the sphere (chi-square against 1 / 4 pi).
TEST(EqualArea, KeepsAreas) {
    auto result = chi2::test(
        [](uint32_t i) -> std::optional<Vec3> {
            return equal_area_square_to_sphere(sample_1d(17, i, 0, 0), sample_1d(17, i, 0, 1));
        },
        [](Vec3) { return 1.0 / (4 * 3.14159265358979323846); }, 300'000);
    EXPECT_GT(result.p_value, 1e-3) << result.summary();
}
