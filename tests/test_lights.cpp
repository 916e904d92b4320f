// Light sampling against its solid-angle density (chi-square) for every light kind, and each
// density's integral over the sphere of directions.
#include <gtest/gtest.h>

#include <cmath>

#include "chi2.h"
#include "math/equal_area.h"
#include "sampling/sampler.h"
#include "sampling/warp.h"
#include "shading/lights.h"
#include "shading/path_vertex.h"
#include "temp_dir.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/engines/render.h"
#include "wavetrace/film/film.h"
#include "wavetrace/image/image.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

constexpr uint32_t kSamples = 300'000;
constexpr double kSignificance = 1e-3;

float u(uint32_t seed, uint32_t i, uint32_t dim) {
    return sample_1d(seed, i, 0, dim);
}

MaterialId add_light(Scene& s, bool two_sided = false) {
    Material m;
    m.kind = MaterialKind::DiffuseLight;
    m.emission = s.add_solid({4, 3, 2});
    m.two_sided = two_sided;
    return s.add_material(m);
}

struct LightCase {
    std::string name;
    Scene scene;
    Point3 ref;
    bool compensated = false;  // the LightSet's MIS compensation
    Normal3 n{0.0f};           // at ref (its light selection); zero: a point in a medium
};

std::vector<LightCase> cases(const TempDir& dir) {
    std::vector<LightCase> out;
    {
        LightCase c{"quad", {}, {0.2f, -0.3f, 2.0f}};  // in front (the normal is about +z)
        c.scene.add_quad(
            {{-1, -0.5f, 1}, {2, 0, 0.3f}, {0, 1.5f, 0.2f}, add_light(c.scene), kNone});
        out.push_back(std::move(c));
    }
    {
        LightCase c{"quad-behind", {}, {0.2f, -0.3f, 0.1f}};  // sees the back: radiance 0
        c.scene.add_quad(
            {{-1, -0.5f, 1}, {2, 0, 0.3f}, {0, 1.5f, 0.2f}, add_light(c.scene), kNone});
        out.push_back(std::move(c));
    }
    {
        LightCase c{"triangle", {}, {0.1f, 0.2f, -0.4f}};
        c.scene.add_mesh({.material = add_light(c.scene, true)},
                         {{-1, -1, 0.5f}, {1.5f, -0.5f, 0.8f}, {0, 1.2f, 0.3f}}, {}, {}, {0, 1, 2});
        out.push_back(std::move(c));
    }
    {
        LightCase c{"sphere-outside", {}, {0, 0, 0}};
        c.scene.add_sphere({{0.5f, 1.2f, 1.0f}, 0.8f, add_light(c.scene), kNone});
        out.push_back(std::move(c));
    }
    {
        LightCase c{"sphere-far", {}, {0, 0, 0}};  // a small cone
        c.scene.add_sphere({{3, 2, 6}, 1.2f, add_light(c.scene), kNone});
        out.push_back(std::move(c));
    }
    {
        LightCase c{"sphere-inside", {}, {0.2f, 0.1f, -0.3f}};
        c.scene.add_sphere({{0, 0, 0}, 1.0f, add_light(c.scene, true), kNone});
        out.push_back(std::move(c));
    }
    {
        LightCase c{"two-lights", {}, {0, 0, 0}};
        MaterialId m = add_light(c.scene);
        c.scene.add_sphere({{0.5f, 1.2f, 1.0f}, 0.6f, m, kNone});
        c.scene.add_quad({{-1, -1, -1}, {2, 0, 0}, {0, 0.5f, 0}, m, kNone});
        out.push_back(c);
        // The same under a sky, seen from a surface: chosen by their importance there.
        c.name = "two-lights-and-sky";
        c.n = normalize(Vec3{0.3f, 1.0f, 0.2f});
        c.scene.background.radiance = Color(0.2f);
        out.push_back(std::move(c));
    }
    {
        LightCase c{"background-constant", {}, {0, 0, 0}};
        c.scene.background.radiance = Color(0.5f);
        out.push_back(std::move(c));
    }
    {
        // An environment map with a bright spot, a gradient and a black band.
        Image env(64, 32);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x) {
                float v = 0.2f + x / 64.0f + (y > 20 && y < 24 ? -1.0f : 0.0f);
                if (std::abs(x - 40) < 3 && std::abs(y - 10) < 3) v = 50.0f;
                env.at(x, y) = Color(std::max(0.0f, v));
            }
        write_image(dir.path() / "env.exr", env);
        LightCase c{"background-environment", {}, {0, 0, 0}};
        c.scene.background.kind = Background::Kind::Environment;
        c.scene.background.radiance = Color(1.0f);
        c.scene.background.rotation = 30.0f;
        c.scene.background.image = c.scene.add_image(read_image(dir.path() / "env.exr"));
        out.push_back(std::move(c));
    }
    {
        // A square equal-area map (a bright spot, a gradient, a black band) in a turned frame.
        Image env(32, 32);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) {
                float v = 0.3f + x / 32.0f + (y > 4 && y < 9 ? -2.0f : 0.0f);
                if (std::abs(x - 22) < 2 && std::abs(y - 12) < 2) v = 40.0f;
                env.at(x, y) = Color(std::max(0.0f, v), 0.5f * std::max(0.0f, v), 0.2f);
            }
        write_image(dir.path() / "equal-area.exr", env);
        LightCase c{"background-equal-area", {}, {0, 0, 0}};
        c.scene.background.kind = Background::Kind::Environment;
        c.scene.background.mapping = Background::Mapping::EqualArea;
        c.scene.background.radiance = Color(1.0f);
        const Vec3 x = normalize(Vec3(0.6f, 0.8f, 0.0f)), z = normalize(Vec3(0.0f, 0.3f, 1.0f));
        const Vec3 zz = normalize(z - dot(z, x) * x);
        c.scene.background.frame = Frame{x, cross(zz, x), zz};
        c.scene.background.image = c.scene.add_image(read_image(dir.path() / "equal-area.exr"));
        out.push_back(std::move(c));
    }
    // The environment maps again, sampled as under MIS (MIS compensation).
    for (size_t i = 0, n = out.size(); i < n; ++i) {
        if (out[i].scene.background.kind != Background::Kind::Environment) continue;
        LightCase c = out[i];
        c.name += "-compensated";
        c.compensated = true;
        out.push_back(std::move(c));
    }
    return out;
}

}  // namespace

TEST(Lights, SamplingMatchesDensityChiSquare) {
    TempDir dir;
    uint32_t seed = 500;
    for (LightCase& c : cases(dir)) {
        LightSet lights(c.scene, c.compensated);
        ++seed;
        auto result = chi2::test(
            [&](uint32_t i) -> std::optional<Vec3> {
                LightSample ls = lights.sample_direction_light(c.scene, c.ref, u(seed, i, 0),
                                                               u(seed, i, 1), u(seed, i, 2));
                if (!ls.valid) return std::nullopt;
                return ls.wi;
            },
            [&](Vec3 w) { return double(lights.pdf_direction(c.scene, c.ref, w)); }, kSamples);
        std::printf("chi2 %-24s %s\n", c.name.c_str(), result.summary().c_str());
        EXPECT_GT(result.p_value, kSignificance) << c.name << ": " << result.summary();
        EXPECT_EQ(result.lost, 0u) << c.name;
    }
}

TEST(Lights, SampledPdfAndRadianceAreConsistent) {
    TempDir dir;
    for (LightCase& c : cases(dir)) {
        LightSet lights(c.scene, c.compensated);
        for (uint32_t i = 0; i < 3000; ++i) {
            LightSample ls = lights.sample(c.scene, c.ref, lights.select(u(3, i, 0), c.ref, c.n),
                                           u(3, i, 1), u(3, i, 2));
            ASSERT_TRUE(ls.valid) << c.name;
            float pdf = ls.prim.valid()
                            ? lights.pdf_prim(c.scene, c.ref, c.n, 0.0f, ls.prim, ls.wi, ls.dist)
                            : lights.pdf_background(c.scene, c.ref, c.n, 0.0f, ls.wi);
            EXPECT_NEAR(ls.pdf, pdf, 2e-3f * pdf) << c.name;
            if (c.name == "quad-behind") {
                EXPECT_EQ(ls.radiance, Color(0.0f));
            }
            if (c.name == "quad") {
                EXPECT_EQ(ls.radiance, Color(4, 3, 2));
            }
        }
    }
}

TEST(Lights, DensityIntegratesToOne) {
    TempDir dir;
    for (LightCase& c : cases(dir)) {
        LightSet lights(c.scene, c.compensated);
        const uint32_t n = 1'000'000;
        double sum = 0, sum2 = 0;
        for (uint32_t i = 0; i < n; ++i) {
            Vec3 w = sample_uniform_sphere(u(21, i, 0), u(21, i, 1));
            double v = lights.pdf_direction(c.scene, c.ref, w) / uniform_sphere_pdf();
            sum += v;
            sum2 += v * v;
        }
        double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
        std::printf("integral %-24s %.5f +- %.5f\n", c.name.c_str(), mean, se);
        EXPECT_NEAR(mean, 1.0, 4 * se) << c.name;
    }
}

// MIS compensation samples a map in proportion to the excess of its radiance over the mean:
// texels below the mean keep only the floor's density, those above gain; a constant map keeps
// its plain distribution (it has no excess). A compensated map's MIS weights are the balance
// heuristic's.
TEST(Lights, CompensationSamplesTheExcessOverTheMean) {
    TempDir dir;
    for (LightCase& c : cases(dir)) {
        if (c.name != "background-environment") continue;
        const LightSet plain(c.scene), compensated(c.scene, true);
        const Background& bg = c.scene.background;
        const ImageData& img = c.scene.images[bg.image];
        // Texel centres: (4, 22) in the black band, (10, 10) dim, (40, 10) the bright spot.
        auto dir_of = [&](int x, int y) {
            return environment_direction(bg, (x + 0.5f) / img.width, (y + 0.5f) / img.height);
        };
        EXPECT_LT(compensated.pdf_background(c.scene, c.ref, c.n, 0.0f, dir_of(10, 10)),
                  0.01f * plain.pdf_background(c.scene, c.ref, c.n, 0.0f, dir_of(10, 10)));
        EXPECT_GT(compensated.pdf_background(c.scene, c.ref, c.n, 0.0f, dir_of(40, 10)),
                  plain.pdf_background(c.scene, c.ref, c.n, 0.0f, dir_of(40, 10)));
        EXPECT_GT(compensated.pdf_background(c.scene, c.ref, c.n, 0.0f, dir_of(4, 22)),
                  0.0f);  // the floor
        // Its MIS weights: the balance heuristic, which the compensation is derived for.
        Estimator mis;
        mis.strategy = Strategy::Mis;
        EXPECT_TRUE(compensated.environment_compensated());
        EXPECT_FALSE(plain.environment_compensated());
        EXPECT_EQ(mis_heuristics(mis, compensated).at_infinity, MisHeuristic::Balance);
        EXPECT_EQ(mis_heuristics(mis, compensated).finite, MisHeuristic::Power);
        EXPECT_EQ(mis_heuristics(mis, plain).at_infinity, MisHeuristic::Power);
    }
    Scene constant;
    Image grey(8, 4);
    for (Color& p : grey.pixels) p = Color(0.5f);
    write_image(dir.path() / "grey.exr", grey);
    constant.background.kind = Background::Kind::Environment;
    constant.background.radiance = Color(1.0f);
    constant.background.image = constant.add_image(read_image(dir.path() / "grey.exr"));
    const Vec3 w = normalize(Vec3{0.3f, 0.5f, -0.2f});
    const Point3 o{0.0f};
    const Normal3 n{0.0f};
    EXPECT_EQ(LightSet(constant, true).pdf_background(constant, o, n, 0.0f, w),
              LightSet(constant).pdf_background(constant, o, n, 0.0f, w));
    EXPECT_FALSE(LightSet(constant, true).environment_compensated());
}

// Two quads facing +z: a bright one (radiance 3, area 1, power 3 pi) at z = 0 and a dim one
// (radiance 1, area 2, power 2 pi) at z = 5.
Scene two_quads() {
    Scene s;
    Material bright;
    bright.kind = MaterialKind::DiffuseLight;
    bright.emission = s.add_solid(Color(3.0f));
    Material dim = bright;
    dim.emission = s.add_solid(Color(1.0f));
    MaterialId b = s.add_material(bright), d = s.add_material(dim);
    s.add_quad({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, b, kNone});
    s.add_quad({{0, 0, 5}, {2, 0, 0}, {0, 1, 0}, d, kNone});
    return s;
}

// A vertex chooses among a few lights by what each could bring it (light_bounds.h): from far
// away along their normals in proportion to radiance x area, as power would; between them only
// the light it is in front of; near the dim one mostly that one. The probabilities sum to 1,
// and select() picks each light as often as its probability says.
TEST(Lights, SelectionFollowsImportanceAtTheVertex) {
    const Scene s = two_quads();
    const LightSet lights(s);
    const PrimRef bright = PrimRef::make(PrimKind::Quad, 0), dim = PrimRef::make(PrimKind::Quad, 1);
    const Normal3 up{0, 0, 1}, none{0.0f};
    const Point3 far{0.5f, 0.5f, 1000.0f};
    EXPECT_NEAR(lights.selection_probability(bright, far, up), 0.6f, 0.01f);
    EXPECT_NEAR(lights.selection_probability(dim, far, none), 0.4f, 0.01f);
    const Point3 between{0.5f, 0.5f, 2.5f};  // behind the dim quad, which faces +z
    EXPECT_EQ(lights.selection_probability(bright, between, up), 1.0f);
    EXPECT_EQ(lights.selection_probability(dim, between, up), 0.0f);
    const Point3 near_dim{1.0f, 0.5f, 5.5f};
    EXPECT_GT(lights.selection_probability(dim, near_dim, up), 0.9f);
    for (uint32_t i = 0; i < 200; ++i) {
        const Point3 p{4.0f * u(5, i, 0) - 2.0f, 4.0f * u(5, i, 1) - 2.0f,
                       8.0f * u(5, i, 2) - 1.0f};
        const Normal3 n = i % 2 ? Normal3{0.0f} : sample_uniform_sphere(u(5, i, 3), u(5, i, 4));
        const float pb = lights.selection_probability(bright, p, n);
        EXPECT_NEAR(pb + lights.selection_probability(dim, p, n), 1.0f, 1e-6f) << i;
        if (i % 20 != 0) continue;
        int picks = 0;
        const int m = 4000;
        for (int k = 0; k < m; ++k) {
            const LightChoice c = lights.select((k + 0.5f) / m, p, n);
            picks += c.index == 0;
            EXPECT_EQ(c.probability, c.index == 0 ? pb : lights.selection_probability(dim, p, n));
            // The same from the choice's sum, with one light's importance evaluated.
            EXPECT_NEAR(lights.selection_probability(c.index == 0 ? bright : dim, p, n, c.total),
                        c.probability, 1e-6f * c.probability);
        }
        EXPECT_NEAR(picks / double(m), pb, 1.0 / m + 1e-6) << i;
    }
}

// The wavefront chooses a chunk's lights at once, the importances with the vertices in lanes:
// the same choices, bit for bit, as one vertex at a time (the megakernel's), for vertices on
// surfaces and in media, lights with and without cones, groups of one light and of several,
// and points that no light reaches (by power).
TEST(Lights, ChoosingManyVerticesAtOnceEqualsOneByOne) {
    Scene s = two_quads();
    std::vector<Point3> positions;
    std::vector<uint32_t> indices;
    for (uint32_t k = 0; k < 6; ++k) {  // a mesh light of six triangles: one group
        const float x = float(k);
        positions.insert(positions.end(), {{x, 0, -3}, {x + 1, 0, -3}, {x, 1, -3}});
        indices.insert(indices.end(), {3 * k, 3 * k + 1, 3 * k + 2});
    }
    s.add_mesh({.material = s.quads[1].material}, positions, {}, {}, indices);
    Light spot;
    spot.kind = Light::Kind::Spot;
    spot.position = {-3, 0, 2};
    spot.direction = normalize(Vec3{1, 0, -1});
    spot.intensity = Color{20.0f};
    s.lights.push_back(spot);
    const LightSet lights(s);
    const LightSelection& selection = lights.selection();
    ASSERT_TRUE(selection.local());
    const size_t n = 61;  // not a whole number of vectors
    float u_select[n], p[3][n], ng[3][n];
    for (uint32_t i = 0; i < n; ++i) {
        u_select[i] = u(11, i, 0);
        const Point3 q{10.0f * u(11, i, 1) - 5.0f, 4.0f * u(11, i, 2) - 2.0f,
                       10.0f * u(11, i, 3) - 5.0f};
        const Normal3 m =
            i % 3 == 0 ? Normal3{0.0f} : sample_uniform_sphere(u(11, i, 4), u(11, i, 5));
        for (int a = 0; a < 3; ++a) {
            p[a][i] = q[a];
            ng[a][i] = m[a];
        }
    }
    // Far behind every one-sided light and outside the spot's cone: no importance anywhere.
    p[0][7] = 3.0f, p[1][7] = 0.5f, p[2][7] = -20.0f;
    ng[0][7] = 0.0f, ng[1][7] = 0.0f, ng[2][7] = 1.0f;
    const float* const p_rows[3] = {p[0], p[1], p[2]};
    const float* const n_rows[3] = {ng[0], ng[1], ng[2]};
    LightChoice at_once[n];
    selection.select_rows(u_select, p_rows, n_rows, n, at_once);
    EXPECT_EQ(at_once[7].total, 0.0f);  // chosen by power
    for (uint32_t i = 0; i < n; ++i) {
        const LightChoice one =
            lights.select(u_select[i], {p[0][i], p[1][i], p[2][i]}, {ng[0][i], ng[1][i], ng[2][i]});
        EXPECT_EQ(at_once[i].index, one.index) << i;
        EXPECT_EQ(at_once[i].probability, one.probability) << i;
        EXPECT_EQ(at_once[i].total, one.total) << i;
    }
}

// The emissive triangles of one material are one group, however many (here 40, more than
// kLocalLights): the group is chosen by its importance, its triangles by their area.
TEST(Lights, AMeshLightIsOneGroupChosenByImportance) {
    Scene s = two_quads();
    const MaterialId dim = s.quads[1].material;
    s.quads.pop_back();
    std::vector<Point3> positions;
    std::vector<uint32_t> indices;
    for (uint32_t k = 0; k < 40; ++k) {  // a strip at z = 5 facing +z, triangles of two sizes
        const float x = float(k), w = k % 2 ? 0.5f : 1.0f;
        positions.insert(positions.end(), {{x, 0, 5}, {x + w, 0, 5}, {x, 1, 5}});
        indices.insert(indices.end(), {3 * k, 3 * k + 1, 3 * k + 2});
    }
    s.add_mesh({.material = dim}, positions, {}, {}, indices);
    const LightSet lights(s);
    ASSERT_EQ(lights.size(), 41u);
    auto tri = [](uint32_t k) { return PrimRef::make(PrimKind::Triangle, k); };
    const PrimRef quad = PrimRef::make(PrimKind::Quad, 0);
    for (uint32_t i = 0; i < 100; ++i) {
        const Point3 p{40.0f * u(9, i, 0) - 5.0f, 4.0f * u(9, i, 1) - 2.0f,
                       8.0f * u(9, i, 2) - 1.0f};
        const Normal3 n = i % 2 ? Normal3{0.0f} : sample_uniform_sphere(u(9, i, 3), u(9, i, 4));
        double total = lights.selection_probability(quad, p, n);
        for (uint32_t k = 0; k < 40; ++k) total += lights.selection_probability(tri(k), p, n);
        EXPECT_NEAR(total, 1.0, 1e-5) << i;
        const float p0 = lights.selection_probability(tri(0), p, n);
        if (p0 > 0.0f) {  // the big triangles twice the small ones, wherever p is
            EXPECT_NEAR(lights.selection_probability(tri(1), p, n) / p0, 0.5f, 1e-5f) << i;
        }
        const int m = 2000;
        int picks = 0;
        for (int k = 0; k < m; ++k) {
            const LightChoice c = lights.select((k + 0.5f) / m, p, n);
            picks += c.index == 40;  // the quad, after the triangles (collect_emitters)
            const PrimRef chosen = c.index < 40 ? tri(uint32_t(c.index)) : quad;
            EXPECT_EQ(c.probability, lights.selection_probability(chosen, p, n));
            EXPECT_NEAR(lights.selection_probability(chosen, p, n, c.total), c.probability,
                        1e-6f * c.probability);
        }
        EXPECT_NEAR(picks / double(m), lights.selection_probability(quad, p, n), 1.0 / m + 1e-6)
            << i;
    }
    // From below the strip (which faces up), behind it: mostly the quad (the group's sphere,
    // 20 across, relaxes the strip's cone; a light of its own there would get none).
    EXPECT_GT(lights.selection_probability(quad, {0.5f, 0.5f, 2.5f}, {0, 0, 1}), 0.9f);
}

// Beyond LightSelection::kLocalLights lights, the choice is in proportion to power everywhere.
TEST(Lights, ManyLightsAreChosenByPower) {
    Scene s = two_quads();
    const MaterialId dim = s.quads[1].material;
    for (size_t k = 2; k <= LightSelection::kLocalLights; ++k)
        s.add_quad({{10.0f + k, 0, 0}, {1, 0, 0}, {0, 1, 0}, dim, kNone});  // power pi each
    const LightSet lights(s);
    const double total = 3 + 2 + (LightSelection::kLocalLights - 1);
    for (const Point3 p : {Point3{0.5f, 0.5f, 2.5f}, Point3{20, 0, 1}}) {
        EXPECT_NEAR(lights.selection_probability(PrimRef::make(PrimKind::Quad, 0), p, {0, 0, 1}),
                    3 / total, 1e-6);
        EXPECT_NEAR(lights.selection_probability(PrimRef::make(PrimKind::Quad, 1), p, {0, 0, 1}),
                    2 / total, 1e-6);
    }
}

// MIS is unbiased only while the density a light sample had equals the density that weighting
// emission found by a BSDF-sampled ray assigns to the same point. For every light kind: a light
// sample from the reference point, then the ray along its direction resolved as either engine
// resolves a segment (resolve_segment, under MIS, after a vertex that sampled lights) finds that
// emitter (or the background) with the sampler's density; and where next_event takes the sample
// in SIMD lanes (quads, spheres from outside, at a Lambertian vertex facing the light) its
// density is the same too.
TEST(Lights, PdfOfEmissionFoundIsTheSamplersPdf) {
    TempDir dir;
    Estimator mis;
    mis.strategy = Strategy::Mis;
    for (LightCase& c : cases(dir)) {
        const LightSet lights(c.scene, c.compensated);
        const Bvh bvh = Bvh::build(c.scene);
        size_t compared = 0;
        for (uint32_t i = 0; i < 2000; ++i) {
            const float us = u(17, i, 0), u1 = u(17, i, 1), u2 = u(17, i, 2);
            const LightSample ls =
                lights.sample(c.scene, c.ref, lights.select(us, c.ref, c.n), u1, u2);
            ASSERT_TRUE(ls.valid) << c.name;
            if (max_component(ls.radiance) <= 0.0f) continue;  // a back face: nothing is found
            const Ray ray{c.ref, ls.wi};
            // Under a sky, a direction sampled from it may find one of the other lights first.
            if (!ls.prim.valid() && bvh.intersect(ray).found()) continue;
            MediumStack media;
            float flight = 0.0f;
            const SegmentResult seg =
                resolve_segment(c.scene, lights, mis, ray, bvh.intersect(ray), media, flight,
                                PreviousVertex{c.ref, 1.0f, false, c.n});
            ASSERT_EQ(seg.event, SegmentEvent::Emission) << c.name << " sample " << i;
            EXPECT_NEAR(seg.emission_pdf_light, ls.pdf, 1e-3f * ls.pdf) << c.name << " " << i;

            Vertex v;
            v.p = c.ref;
            v.ng = ls.wi;
            v.frame = Frame::from_normal(ls.wi);
            v.bsdf.albedo = Color(0.5f);
            VertexSamples vs{};
            vs.light_select = us;
            vs.light_u = u1;
            vs.light_v = u2;
            const DirectSample d = next_event(c.scene, lights, mis, v, ls.wi, vs);
            // The vertex's normal may choose another light than c.n's: the light sample it takes.
            const LightSample at_v =
                lights.sample(c.scene, c.ref, lights.select(us, c.ref, v.ng), u1, u2);
            if (!(max_component(at_v.radiance) > 0.0f) || !(dot(at_v.wi, v.ng) > 0.0f)) continue;
            ASSERT_TRUE(d.valid) << c.name << " " << i;
            EXPECT_NEAR(d.pdf_light, at_v.pdf, 1e-4f * at_v.pdf) << c.name << " " << i;
            if (at_v.prim.bits != ls.prim.bits || !(at_v.wi == ls.wi)) continue;
            // Both techniques weigh the direction by one heuristic (the light sample's by its
            // shadow ray's length, the emission's by the segment's end), so that their weights
            // sum to 1 for any BSDF density — the emission found after this vertex.
            media = MediumStack{};
            const SegmentResult seg_v =
                resolve_segment(c.scene, lights, mis, ray, bvh.intersect(ray), media, flight,
                                PreviousVertex{c.ref, 1.0f, false, v.ng});
            const MisHeuristics h = mis_heuristics(mis, lights);
            ASSERT_EQ(std::isinf(d.shadow.tmax), seg.at_infinity) << c.name << " " << i;
            const float pdf_bsdf = 0.7f * ls.pdf;
            EXPECT_NEAR(direct_weight(Strategy::Mis, h.of(std::isinf(d.shadow.tmax)), d.pdf_light,
                                      pdf_bsdf) +
                            emission_weight(Strategy::Mis, h.of(seg.at_infinity), false, pdf_bsdf,
                                            seg_v.emission_pdf_light),
                        1.0f, 1e-3f)
                << c.name << " " << i;
            ++compared;
        }
        if (c.name == "quad-behind") {
            EXPECT_EQ(compared, 0u);  // it sees only the light's back
        } else {
            EXPECT_GT(compared, 1000u) << c.name;
        }
    }
}

// An equal-area map is seen in its own frame, each direction at its nearest texel (pbrt-v4's
// lookup): the direction of a texel's centre, turned into the world by the frame, sees that
// texel exactly, and the same direction without the frame another one.
TEST(Lights, EqualAreaMapsAreSeenInTheirFrameAtTheNearestTexel) {
    TempDir dir;
    for (LightCase& c : cases(dir)) {
        if (c.name != "background-equal-area") continue;
        const Background& bg = c.scene.background;
        const ImageData& img = c.scene.images[bg.image];
        for (auto [x, y] : {std::pair{22, 12}, {3, 30}, {16, 16}, {31, 0}, {10, 6}}) {
            const Vec3 local = equal_area_square_to_sphere((x + 0.5f) / 32, (y + 0.5f) / 32);
            const Vec3 world = bg.frame->to_world(local);
            EXPECT_EQ(eval_background(c.scene, world), img.texel(x, y)) << x << " " << y;
            const Vec2 uv = environment_uv(bg, world);
            EXPECT_NEAR(uv.x, (x + 0.5f) / 32, 1e-5f);
            EXPECT_NEAR(uv.y, (y + 0.5f) / 32, 1e-5f);
        }
        const Color bright = img.texel(22, 12);
        Scene unframed = std::move(c.scene);
        unframed.background.frame.reset();
        const Vec3 spot = equal_area_square_to_sphere(22.5f / 32, 12.5f / 32);
        EXPECT_EQ(eval_background(unframed, spot), bright);
        EXPECT_NE(eval_background(unframed, Frame{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}.to_world(spot)),
                  bright);
        return;
    }
    FAIL() << "no equal-area case";
}

// A light seen at a grazing angle from a point whose shadow-ray origin is offset towards the
// light's plane (a wall 10 units from the origin, where the offset is 2.2e-4): the shadow ray
// must still end short of the light, so that next-event estimation finds it as BSDF sampling
// does. A 1 x 1 image aimed at the point, direct light only, NEE against BSDF sampling with
// the variances of both means: with rays aimed along the direction from the unmoved point, the
// offset carried them across the light and NEE lost most of it.
namespace {

// The one pixel's green by NEE and by BSDF sampling, direct light alone (max_depth 2), and
// their difference in standard errors; the BSDF's estimate must find light.
double nee_against_bsdf(
    const Scene& s, const Bvh& bvh, uint32_t spp, uint32_t seed, Engine engine, const char* what) {
    auto render_with = [&](Strategy strategy) {
        RenderRequest r;
        r.width = r.height = 1;
        r.spp = spp;
        r.seed = seed;
        r.engine = engine;
        r.estimator.strategy = strategy;
        r.estimator.max_depth = 2;
        Film film(1, 1);
        render(s, bvh, r, film);
        return std::make_pair(film.mean().at(0, 0).y, film.variance_of_mean().at(0, 0).y);
    };
    const auto [nee, var_nee] = render_with(Strategy::Nee);
    const auto [bsdf, var_bsdf] = render_with(Strategy::Bsdf);
    const double z = (nee - bsdf) / std::sqrt(double(var_nee) + var_bsdf);
    std::printf("%s: NEE %.5f, BSDF %.5f, z %.2f\n", what, nee, bsdf, z);
    EXPECT_GT(bsdf, 0.0f);
    return z;
}

}  // namespace

TEST(Lights, NeeFindsALightSeenAtAGrazingAngle) {
    Scene s;
    Material wall;
    wall.albedo = s.add_solid(Color(0.8f));
    const Point3 p{0.0f, 0.0f, -10.0f};
    s.add_quad({{-5, -5, -10}, {10, 0, 0}, {0, 10, 0}, s.add_material(wall), kNone});
    // The light's centre 3 away along w, its normal 78 degrees from -w, leaning against +z.
    const Vec3 w = normalize(Vec3(0.3f, 0.0f, 1.0f)), ng{0.0f, 0.0f, 1.0f};
    const Vec3 t = -normalize(ng - dot(ng, w) * w);
    const Vec3 n = normalize(-0.2f * w + 0.98f * t);
    const Vec3 a = normalize(cross(n, Vec3(0.0f, 1.0f, 0.0f))), b = cross(n, a);
    const Point3 c = p + 3.0f * w;
    s.add_quad({c - 0.5f * a - 0.5f * b, a, b, add_light(s), kNone});
    ASSERT_GT(dot(cross(a, b), n), 0.99f);  // facing the wall point
    s.camera.look_from = p + Vec3(0.0f, 0.3f, 2.0f);
    s.camera.look_at = p;
    s.camera.vfov = 0.01f;
    const Bvh bvh = Bvh::build(s);
    EXPECT_LT(std::fabs(nee_against_bsdf(s, bvh, 200'000, 4, Engine::Wavefront, "grazing light")),
              4.0);
}

// A metallic-roughness emitter under a clearcoat of weight k emits Le (1 - k Fc) towards V,
// Fc = 0.04 + 0.96 (1 - N.V)^5 (KHR_materials_clearcoat): its light samples carry that radiance
// at every angle, and light found by sampling the light and by sampling the BSDF agree in both
// engines (the lanes, which take emitters of one radiance, leave it to the scalar code).
TEST(Lights, ClearcoatDarkensEmissionByItsFresnel) {
    Scene s;
    Material lamp;
    lamp.kind = MaterialKind::MetallicRoughness;
    lamp.albedo = s.add_solid(Color(0.0f));
    lamp.emission = s.add_solid({4, 3, 2});
    lamp.clearcoat = 0.5f;
    s.add_quad({{-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, s.add_material(lamp), kNone});  // faces +z
    LightSet lights(s, false);
    for (const float cos_v : {1.0f, 0.6f, 0.2f, 0.05f}) {
        const Point3 ref{0.0f, -4.0f * std::sqrt(1.0f - cos_v * cos_v), 4.0f * cos_v};
        const double fc = 0.04 + 0.96 * std::pow(1.0 - cos_v, 5.0);
        const LightSample ls =
            lights.sample(s, ref, lights.select(0.5f, ref, Normal3{0.0f}), 0.5f, 0.5f);
        ASSERT_TRUE(ls.valid);
        ASSERT_NEAR(dot(-ls.wi, Vec3(0, 0, 1)), cos_v, 1e-5f);
        for (int a = 0; a < 3; ++a)
            EXPECT_NEAR(ls.radiance[a], Color(4, 3, 2)[a] * (1.0 - 0.5 * fc), 1e-5) << cos_v;
    }

    // A grey wall lit by the coated lamp at angles from head-on to grazing.
    Material wall;
    wall.albedo = s.add_solid(Color(0.8f));
    s.add_quad({{-6, 3, -6}, {12, 0, 0}, {0, 0, 12}, s.add_material(wall), kNone});
    s.camera.look_from = {0.0f, -6.0f, 0.5f};
    s.camera.look_at = {0.0f, 3.0f, 0.5f};
    s.camera.up = {0.0f, 0.0f, 1.0f};
    s.camera.vfov = 1.0f;
    const Bvh bvh = Bvh::build(s);
    for (const Engine engine : {Engine::Wavefront, Engine::Megakernel})
        EXPECT_LT(std::fabs(nee_against_bsdf(s, bvh, 100'000, 5, engine, "coated light")), 4.0);
}
