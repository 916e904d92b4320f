#include <gtest/gtest.h>

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
