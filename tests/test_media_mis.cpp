// MIS weights' guards, and the medium building blocks: free-flight sampling, analytic
// transmittance through nested boundaries, and the media found around a point.
#include <gtest/gtest.h>

#include <cmath>

#include "sampling/sampler.h"
#include "shading/mis.h"
#include "shading/path_vertex.h"
#include "shading/trace.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

TEST(Mis, HeuristicsAndGuards) {
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Balance, 1, 3), 0.25f);
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Power, 1, 3), 0.1f);
    EXPECT_FLOAT_EQ(mis_weight(MisHeuristic::Power, 3, 1) + mis_weight(MisHeuristic::Power, 1, 3),
                    1.0f);
    EXPECT_EQ(mis_weight(MisHeuristic::Power, INFINITY, 5), 1.0f);
    EXPECT_EQ(mis_weight(MisHeuristic::Power, 5, INFINITY), 0.0f);
    EXPECT_EQ(mis_weight(MisHeuristic::Balance, 0, 0), 0.0f);
    EXPECT_EQ(mis_weight(MisHeuristic::Balance, 2, 0), 1.0f);
    EXPECT_EQ(mis_weight(MisHeuristic::Power, NAN, 1), 0.0f);
    // Huge densities whose squares overflow a float still give a finite weight.
    EXPECT_NEAR(mis_weight(MisHeuristic::Power, 1e30f, 1e30f), 0.5f, 1e-6f);
}

TEST(Media, FreeFlightIsExponential) {
    // Mean -ln(1-u)/sigma = 1/sigma; P(s > 1/sigma) = 1/e.
    const float sigma = 0.25f;
    const int n = 200000;
    double sum = 0;
    int beyond = 0;
    for (int i = 0; i < n; ++i) {
        float s = sample_free_flight(sigma, sample_1d(5, i, 0, 0));
        sum += s;
        beyond += s > 1 / sigma;
    }
    double mean = sum / n, se = (1 / sigma) / std::sqrt(double(n));
    EXPECT_NEAR(mean, 1 / sigma, 4 * se);
    double p = double(beyond) / n, se_p = std::sqrt(std::exp(-1.0) * (1 - std::exp(-1.0)) / n);
    EXPECT_NEAR(p, std::exp(-1.0), 4 * se_p);
}

namespace {
// Fog (density 0.1) in a box [-10, 10]^3 holding smoke (density 0.5) in a box [-1, 1]^3, and
// an opaque wall at x = 20.
Scene nested_media() {
    Scene s;
    MediumId fog = s.add_medium("fog", 0.1f, s.add_solid(Color(1.0f)));
    MediumId smoke = s.add_medium("smoke", 0.5f, s.add_solid(Color(1.0f)));
    MaterialId interface = s.interface_material();
    s.add_box({-10, -10, -10}, {10, 10, 10}, interface, fog);
    s.add_box({-1, -1, -1}, {1, 1, 1}, interface, smoke);
    Material wall;
    wall.kind = MaterialKind::Lambertian;
    wall.albedo = s.add_solid(Color(0.5f));
    s.add_quad({{20, -5, -5}, {0, 10, 0}, {0, 0, 10}, s.add_material(wall), kNone});
    return s;
}
}  // namespace

TEST(Media, TransmittanceIsAnalyticThroughNestedBoundaries) {
    Scene s = nested_media();
    Bvh bvh = Bvh::build(s);
    uint64_t rays = 0;
    // From the centre (inside smoke inside fog) out along +y to y = 15: 1 unit of smoke, 9 of
    // fog, 5 of vacuum.
    MediumStack media = media_at(s, bvh, {0, 0, 0});
    ASSERT_EQ(media.size, 2);
    EXPECT_EQ(media.current(), 1u);  // smoke, innermost
    Color t = transmittance(s, bvh, Ray{{0, 0, 0}, {0, 1, 0}, 0, 15}, media, true, &rays);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(t[c], std::exp(-0.5f * 1 - 0.1f * 9), 1e-4f);
    // Along +x the wall at x = 20 blocks.
    EXPECT_EQ(transmittance(s, bvh, Ray{{0, 0, 0}, {1, 0, 0}, 0, 25}, media, true, &rays),
              Color(0.0f));
    // From outside everything, across both boxes: 18 units of fog, 2 of smoke.
    MediumStack outside = media_at(s, bvh, {0, 0, -30});
    EXPECT_EQ(outside.size, 0);
    float across =
        transmittance(s, bvh, Ray{{0, 0.5f, -30}, {0, 0, 1}, 0, 60}, outside, true, &rays).x;
    EXPECT_NEAR(across, std::exp(-0.1f * 18 - 0.5f * 2), 1e-4f);
}

TEST(Media, UnboundedShadowRaysAbsorbUnlessTheMediumIsEmpty) {
    // A shadow ray to the environment (tmax infinity) from inside a medium that fills the scene
    // with nothing around it: a medium that extinguishes anything absorbs it all; one of
    // density 0 (possible from the C++ API) lets it all through, as the free-flight sampling
    // does, which never scatters there and lets the path reach the background.
    for (float density : {0.0f, 0.3f}) {
        Scene s;
        const MediumId m = s.add_medium("m", density, s.add_solid(Color(1.0f)));
        MediumStack media;
        media.push(m);
        Material wall;
        wall.kind = MaterialKind::Lambertian;
        wall.albedo = s.add_solid(Color(0.5f));
        s.add_quad({{20, -5, -5}, {0, 10, 0}, {0, 0, 10}, s.add_material(wall), kNone});
        Bvh bvh = Bvh::build(s);
        uint64_t rays = 0;
        const Ray escape{{0, 0, 0}, {0, 1, 0}, 0, kInfinity};
        const Color expected(density > 0 ? 0.0f : 1.0f);
        EXPECT_EQ(transmittance(s, bvh, escape, media, true, &rays), expected) << density;
        EXPECT_EQ(transmittance_walk(s, bvh, escape, media, &rays), expected) << density;
        // A bounded one: exp(-density * 4) either way.
        EXPECT_FLOAT_EQ(
            transmittance(s, bvh, Ray{{0, 0, 0}, {0, 2, 0}, 0, 2}, media, true, &rays).y,
            std::exp(-density * 4));
        float flight = 1.0f, dist = 0;
        Color weight;
        EXPECT_EQ(scatters_in_medium(s, m, escape, Hit{}, 1.0f, flight, &dist, &weight),
                  density > 0);
    }
}
