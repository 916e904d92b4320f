// Tangent frames, normal maps and bump maps (scene/hit_geometry.h, scene/normal_maps.h): the
// tangents follow the uv mapping, a flat normal map changes nothing, a tilted one and a height
// ramp tilt the normal as their formulas say, a clearcoat keeps a normal of its own, and both
// engines agree on a mapped scene (the
// engine-equality tests run scenes/materials.json, whose earth sphere is bump-mapped and whose
// tiles are normal-mapped).
#include <gtest/gtest.h>

#include <cmath>

#include "bsdfs/bump_terminator.h"
#include "bsdfs/lane_lobe.h"
#include "scene/hit_geometry.h"
#include "scene/normal_maps.h"
#include "shading/lights.h"
#include "shading/path_vertex.h"
#include "temp_dir.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"
#include "wavetrace/shading/surface.h"

using namespace wavetrace;

namespace {

void expect_near(Vec3 a, Vec3 b, float tol, const char* what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

// A quad [0, 1]^2 in z = 0 facing +z added to s, of a material with the given maps.
Scene quad_scene(Scene s, Material m) {
    m.albedo = s.add_solid(Color(0.5f));
    const MaterialId id = s.add_material(m);
    s.add_quad({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, id});
    return s;
}

SurfaceHit hit_quad(const Scene& s, float u, float v) {
    Hit h{1.0f, PrimRef::make(PrimKind::Quad, 0), u, v};
    return surface_at(s, Ray{{u, v, 1}, {0, 0, -1}}, h);
}

MappedPoint mapped(const SurfaceHit& h) {
    return {h.p, h.ng, h.ns, h.uv, h.dpdu, h.dpdv};
}

}  // namespace

// A triangle's dp/du, dp/dv from its uvs: moving the point by eps dp/du moves its uv by (eps, 0).
TEST(Tangents, TriangleFollowsItsUvs) {
    Scene s;
    Mesh mesh;
    mesh.material = s.add_material(Material{});
    s.add_mesh(mesh, {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}}, {},
               {{0.1f, 0.2f}, {0.1f, 0.7f}, {0.6f, 0.2f}}, {0, 1, 2});
    const PrimRef tri = PrimRef::make(PrimKind::Triangle, 0);
    const Tangents t = hit_tangents(s, tri, {0.4f, 0.9f, 0});
    // u grows along the third vertex's edge (0, 3, 0) by 0.5: dp/du = (0, 6, 0); v along x.
    expect_near(t.dpdu, {0, 6, 0}, 1e-5f, "dpdu");
    expect_near(t.dpdv, {4, 0, 0}, 1e-5f, "dpdv");
    // Without uvs the edges are the tangents.
    Scene plain;
    Mesh m2;
    m2.material = plain.add_material(Material{});
    plain.add_mesh(m2, {{0, 0, 0}, {2, 0, 0}, {0, 3, 0}}, {}, {}, {0, 1, 2});
    const Tangents e = hit_tangents(plain, tri, {0.4f, 0.9f, 0});
    expect_near(e.dpdu, {2, 0, 0}, 0, "edge 1");
    expect_near(e.dpdv, {0, 3, 0}, 0, "edge 2");
}

// A sphere's tangents are those of sphere_uv's mapping: a step along dp/du (dp/dv) changes u (v)
// by the step over |dp/du|^2 and leaves the other coordinate as it is.
TEST(Tangents, SphereFollowsItsMapping) {
    Scene s;
    s.add_sphere({{1, 2, 3}, 2.0f, s.add_material(Material{})});
    const PrimRef sphere = PrimRef::make(PrimKind::Sphere, 0);
    for (Vec3 n : {normalize(Vec3{0.3f, 0.4f, 0.8f}), normalize(Vec3{-0.7f, -0.2f, 0.3f})}) {
        const Point3 p = Point3{1, 2, 3} + 2.0f * n;
        const Tangents t = hit_tangents(s, sphere, p);
        EXPECT_NEAR(dot(t.dpdu, n), 0.0f, 1e-5f);
        EXPECT_NEAR(dot(t.dpdv, n), 0.0f, 1e-5f);
        const Vec2 uv = sphere_uv(n);
        const float eps = 1e-3f;
        const Vec2 a = sphere_uv(normalize(p + eps * t.dpdu / length(t.dpdu) - Point3{1, 2, 3}));
        const Vec2 b = sphere_uv(normalize(p + eps * t.dpdv / length(t.dpdv) - Point3{1, 2, 3}));
        EXPECT_NEAR((a.x - uv.x) * length(t.dpdu), eps, 2e-5f);
        EXPECT_NEAR(a.y - uv.y, 0.0f, 2e-5f);
        EXPECT_NEAR((b.y - uv.y) * length(t.dpdv), eps, 2e-5f);
        EXPECT_NEAR(b.x - uv.x, 0.0f, 2e-5f);
    }
}

// The same for pbrt-v4's mapping (SphereMapping::ZUp) in a sphere's own frame, its transform's
// rotation: here its +z turned to world +x.
TEST(Tangents, TurnedZUpSphereFollowsItsMapping) {
    Scene s;
    Sphere sphere{{0, 0, 0}, 1.0f, s.add_material(Material{})};
    sphere.mapping = SphereMapping::ZUp;
    s.add_sphere(sphere, Transform::rotate({0, 1, 0}, 90));
    s.add_sphere(sphere, Transform::translate({1, 2, 3}) * Transform::scale(Vec3(2.0f)));
    ASSERT_EQ(s.sphere_frames.size(), 1u);
    ASSERT_EQ(s.spheres[1].frame, kNone);
    // The pole (+z in its frame, v = 1) is at world +x; u = 0 (its +x) at world -z.
    const Vec2 pole = sphere_uv(s, s.spheres[0], {1, 0, 0});
    EXPECT_NEAR(pole.y, 1.0f, 1e-6f);
    const Vec2 seam = sphere_uv(s, s.spheres[0], {0, 0, -1});
    EXPECT_NEAR(seam.x, 0.0f, 1e-6f);
    EXPECT_NEAR(seam.y, 0.5f, 1e-6f);
    for (size_t i : {0u, 1u}) {
        const Sphere& sp = s.spheres[i];
        const PrimRef prim = PrimRef::make(PrimKind::Sphere, static_cast<uint32_t>(i));
        for (Vec3 n : {normalize(Vec3{0.3f, 0.4f, 0.8f}), normalize(Vec3{-0.7f, -0.2f, 0.3f})}) {
            const Point3 p = sp.center + sp.radius * n;
            const Tangents t = hit_tangents(s, prim, p);
            EXPECT_NEAR(dot(t.dpdu, n), 0.0f, 1e-5f);
            EXPECT_NEAR(dot(t.dpdv, n), 0.0f, 1e-5f);
            const Vec2 uv = sphere_uv(s, sp, n);
            const float eps = 1e-3f;
            const Vec2 a = sphere_uv(s, sp, normalize(p + eps * t.dpdu / length(t.dpdu) - sp.center));
            const Vec2 b = sphere_uv(s, sp, normalize(p + eps * t.dpdv / length(t.dpdv) - sp.center));
            EXPECT_NEAR((a.x - uv.x) * length(t.dpdu), eps, 4e-5f) << i;
            EXPECT_NEAR(a.y - uv.y, 0.0f, 2e-5f) << i;
            EXPECT_NEAR((b.y - uv.y) * length(t.dpdv), eps, 4e-5f) << i;
            EXPECT_NEAR(b.x - uv.x, 0.0f, 2e-5f) << i;
        }
    }
}

// (0.5, 0.5, 1) is the unperturbed normal; (0.75, 0.5, 1) tilts it towards +u by atan(0.5), and
// (0.5, 0.25, 1) towards -v.
TEST(NormalMaps, NormalMapTiltsInTheTangentFrame) {
    for (const auto& [rgb, expected] :
         {std::pair{Color(0.5f, 0.5f, 1.0f), Vec3{0, 0, 1}},
          std::pair{Color(0.75f, 0.5f, 1.0f), normalize(Vec3{0.5f, 0, 1})},
          std::pair{Color(0.5f, 0.25f, 1.0f), normalize(Vec3{0, -0.5f, 1})}}) {
        Scene s;
        Material m;
        m.normal_map = s.add_solid(rgb);
        s = quad_scene(s, m);
        const SurfaceHit h = hit_quad(s, 0.3f, 0.6f);
        expect_near(mapped_normal(s, s.materials[0], mapped(h), {0, 0, 1}), expected, 1e-6f,
                    "normal map");
    }
}

// Heights rising along u with slope k tilt the normal to normalize(-k, 0, 1).
TEST(NormalMaps, BumpRampTiltsAgainstItsSlope) {
    Scene s;
    ImageData ramp;
    ramp.width = 64;
    ramp.height = 1;
    for (int x = 0; x < 64; ++x) ramp.texels.push_back(Color(x / 64.0f));
    Texture t;
    t.kind = TextureKind::Image;
    t.image = s.add_image(ramp);
    Material m;
    m.bump_map = s.add_texture(t);
    m.bump_scale = 0.1f;
    m.albedo = s.add_solid(Color(0.5f));
    s.add_quad({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, s.add_material(m)});
    // Between texel centres the bilinear ramp rises by 1/64 per 1/64 of u: slope 0.1.
    const SurfaceHit h = hit_quad(s, 0.4f, 0.5f);
    expect_near(mapped_normal(s, s.materials[0], mapped(h), {0, 0, 1}),
                normalize(Vec3{-0.1f, 0, 1}), 1e-4f, "bump");
    // A quad without maps has no tangents computed, and its normal stays.
    Scene plain = quad_scene(Scene{}, Material{});
    const SurfaceHit p = hit_quad(plain, 0.4f, 0.5f);
    EXPECT_EQ(length_squared(p.dpdu), 0.0f);
}

// Where the shading normal tilts far from the geometric one, a mirror reflects wo to below the
// geometric surface: with the geometric-side test (our default) that direction carries nothing,
// without it (pbrt-v4's and Mitsuba 3's rule, which their readers set) the path goes on.
TEST(ShadingNormals, GeometricSideTestIsTheScenesChoice) {
    Scene s;
    const LightSet lights(s);
    Vertex v;
    v.ng = {0, 0, 1};
    v.frame = Frame::from_normal(normalize(Vec3{0.8f, 0, 0.6f}));
    v.bsdf.kind = MaterialKind::Mirror;
    v.bsdf.albedo = Color(1.0f);
    const Vec3 wo = normalize(Vec3{-0.3f, 0, 0.954f});
    const ContinuationSamples u{0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    const Continuation tested = sample_continuation(Strategy::Bsdf, s, lights, v, wo, u);
    EXPECT_FALSE(tested.valid);
    v.geometric_side_test = false;
    const Continuation free = sample_continuation(Strategy::Bsdf, s, lights, v, wo, u);
    ASSERT_TRUE(free.valid);
    EXPECT_LT(free.wi.z, 0.0f);  // below the geometric surface
}

// An anisotropic conductor's roughness runs along dp/du: its vertex frame's s is dp/du made
// perpendicular to the shading normal (here a quad's u edge, where the basis built from the
// normal alone would give +x).
TEST(ShadingNormals, AnisotropicRoughnessFollowsDpDu) {
    TempDir dir;
    auto scene = [&](const std::string& roughness) {
        return dir.write("s.json", R"({"camera": {"look_from": [0, 0, 5], "look_at": [0, 0, 0]},
            "materials": {"brushed": {"type": "conductor", "metal": "Al", )" + roughness + R"(}},
            "objects": [{"type": "quad", "q": [0, 0, 0], "u": [0, 2, 0], "v": [-1, 0, 0],
                         "material": "brushed"}]})");
    };
    const Scene s = load_scene(scene(R"("alpha_u": 0.3, "alpha_v": 0.05)"));
    EXPECT_EQ(s.materials[0].alpha_u, 0.3f);
    EXPECT_EQ(s.materials[0].alpha_v, 0.05f);
    const Ray ray{{-0.5f, 0.5f, 3}, {0, 0, -1}};
    const Hit hit_of_ray{3.0f, PrimRef::make(PrimKind::Quad, 0), 0.25f, 0.5f};
    const SurfaceHit hit = surface_at(s, ray, hit_of_ray);
    const Vertex v = surface_vertex(s, hit, -ray.d);
    EXPECT_NEAR(v.frame.s.y, 1.0f, 1e-6f);
    EXPECT_NEAR(v.frame.n.z, 1.0f, 1e-6f);
    EXPECT_NEAR(dot(cross(v.frame.s, v.frame.t), v.frame.n), 1.0f, 1e-6f);
    for (const char* bad : {R"("alpha": 0.1, "alpha_u": 0.3, "alpha_v": 0.05)", R"("alpha_u": 0.3)"}) {
        try {
            load_scene(scene(bad));
            ADD_FAILURE() << bad;
        } catch (const SceneError&) {
        }
    }
    // alpha_u from a uv checker: the vertex reads it at the hit's (u, v); the frame still
    // follows dp/du.
    const Scene t = load_scene(scene(R"("alpha_u": {"type": "uv_checker", "scale": 0.5,
        "even": 0.02, "odd": 0.7}, "alpha_v": 0.05)"));
    ASSERT_NE(t.materials[0].alpha_u_texture, kNone);
    EXPECT_EQ(t.materials[0].alpha_v_texture, kNone);
    const Vertex tv = surface_vertex(t, surface_at(t, ray, hit_of_ray), -ray.d);
    const float cell = eval_texture(t, t.materials[0].alpha_u_texture, hit.uv, hit.p).x;
    EXPECT_TRUE(cell == 0.02f || cell == 0.7f) << cell;
    EXPECT_EQ(tv.bsdf.alpha, cell);
    EXPECT_EQ(tv.bsdf.alpha_v, 0.05f);
    EXPECT_NEAR(tv.frame.s.y, 1.0f, 1e-6f);
}

// Mitsuba 3's flip_invalid_normals: a mapped normal n facing away from the viewer (wo on the
// unperturbed normal's side but not on n's) is mirrored about the unperturbed normal; a viewer
// that n faces, or a material without the switch, keeps n.
TEST(NormalMaps, InvalidNormalsAreMirroredWhereAsked) {
    for (const bool flip : {false, true}) {
        Scene s;
        Material m;
        m.normal_map = s.add_solid(Color(0.95f, 0.5f, 1.0f));  // (0.9, 0, 1) in the tangent frame
        m.flip_invalid_normals = flip;
        s = quad_scene(s, m);
        const SurfaceHit h = hit_quad(s, 0.3f, 0.6f);
        const Vec3 tilted = normalize(Vec3{0.9f, 0, 1}), mirrored = normalize(Vec3{-0.9f, 0, 1});
        const Vec3 grazing_back = normalize(Vec3{-1, 0, 0.3f});  // below the tilted normal
        ASSERT_LT(dot(grazing_back, tilted), 0.0f);
        expect_near(mapped_normal(s, s.materials[0], mapped(h), grazing_back),
                    flip ? mirrored : tilted, 1e-6f, flip ? "flipped" : "kept");
        expect_near(mapped_normal(s, s.materials[0], mapped(h), normalize(Vec3{1, 0, 0.3f})),
                    tilted, 1e-6f, "facing");
    }
}

// Estevez et al. 2019: a normal bent by theta_n stands for a GGX surface of alpha^2 =
// tan^2(theta_n) / 8 (at most 1), whose Smith masking 2 / (1 + sqrt(1 + alpha^2 tan^2 theta_i))
// scales light from theta_i off the unperturbed normal; nothing where wi lies on different sides
// of the two normals, and no change without a bend.
TEST(NormalMaps, BumpShadowingIsEstevezMasking) {
    const float pi = 3.14159265f;
    auto at = [](float degrees) {  // a direction in the xz-plane, degrees from +z towards +x
        const float a = degrees * 3.14159265f / 180.0f;
        return Vec3{std::sin(a), 0, std::cos(a)};
    };
    const Normal3 n0{0, 0, 1}, n = at(30);
    const float alpha2 = bump_shadowing_alpha2(n0, n);
    EXPECT_NEAR(alpha2, std::pow(std::tan(pi / 6), 2.0f) / 8, 1e-6f);
    EXPECT_EQ(bump_shadowing_alpha2(n0, at(80)), 1.0f);  // tan^2 80 / 8 = 4: clamped
    EXPECT_NEAR(bump_shadowing(n0, n, alpha2, n0), 1.0f, 1e-6f);
    EXPECT_NEAR(bump_shadowing(n0, n, alpha2, at(60)), 2 / (1 + std::sqrt(1 + alpha2 * 3)), 1e-6f);
    EXPECT_LT(bump_shadowing(n0, n, alpha2, at(85)), bump_shadowing(n0, n, alpha2, at(60)));
    EXPECT_EQ(bump_shadowing(n0, n, alpha2, at(-70)), 0.0f);  // above n0, below n
    EXPECT_EQ(bump_shadowing(n0, n0, 0.0f, at(-89)), 1.0f);

    // At a vertex: a Lambertian quad whose normal map bends its normal by 30 degrees about y;
    // light from 60 degrees is scaled by the masking, with the switch and only with it.
    auto direct = [&](bool shadowing) {
        Scene s;
        Material m;
        m.normal_map = s.add_solid(0.5f * (at(30) + Vec3(1.0f)));
        m.bump_shadowing = shadowing;
        s = quad_scene(s, m);
        const Vertex v = surface_vertex(s, hit_quad(s, 0.3f, 0.6f), {0, 0, 1});
        EXPECT_NEAR(v.bump_alpha2, shadowing ? alpha2 : 0.0f, 1e-6f);
        LightSample ls;
        ls.wi = at(60);
        ls.dist = 1.0f;
        ls.radiance = Color(1.0f);
        ls.pdf = 1.0f;
        ls.valid = true;
        return direct_sample_from(v, {0, 0, 1}, ls).value.x;
    };
    const float plain = direct(false);
    ASSERT_GT(plain, 0.0f);
    EXPECT_NEAR(direct(true) / plain, 2 / (1 + std::sqrt(1 + alpha2 * 3)), 1e-5f);
}

// KHR_materials_clearcoat: without a clearcoatNormalTexture the coat keeps the unperturbed
// normal under a normal-mapped base; with one it tilts by that map in the same tangent frame.
// The vertex holds the coat's normal in its shading frame; (0, 0, 1) where nothing is mapped.
TEST(NormalMaps, ClearcoatKeepsANormalOfItsOwn) {
    const Vec3 wo{0, 0, 1};
    auto vertex = [&](const Scene& s) { return surface_vertex(s, hit_quad(s, 0.3f, 0.6f), wo); };
    Material coated;
    coated.kind = MaterialKind::MetallicRoughness;
    coated.roughness = 0.5f;
    coated.clearcoat = 1.0f;
    coated.clearcoat_roughness = 0.1f;
    {
        const Scene s = quad_scene(Scene{}, coated);
        EXPECT_TRUE(vertex(s).bsdf.coat_along_normal());
    }
    {
        Scene s;
        Material m = coated;
        m.normal_map = s.add_solid(Color(0.75f, 0.5f, 1.0f));  // the base tilts towards +u
        s = quad_scene(s, m);
        const Vertex v = vertex(s);
        expect_near(v.frame.n, normalize(Vec3{0.5f, 0, 1}), 1e-6f, "base");
        expect_near(v.frame.to_world(v.bsdf.coat_normal), {0, 0, 1}, 1e-6f, "coat unmapped");
        EXPECT_FALSE(is_lane_bsdf(v.bsdf));  // the lanes' coats lie along the shading normal
    }
    {
        Scene s;
        Material m = coated;
        m.normal_map = s.add_solid(Color(0.75f, 0.5f, 1.0f));
        m.clearcoat_normal_map = s.add_solid(Color(0.5f, 0.25f, 1.0f));  // towards -v
        s = quad_scene(s, m);
        const Vertex v = vertex(s);
        expect_near(coat_normal(s, s.materials[0], mapped(hit_quad(s, 0.3f, 0.6f))),
                    normalize(Vec3{0, -0.5f, 1}), 1e-6f, "coat map");
        expect_near(v.frame.to_world(v.bsdf.coat_normal), normalize(Vec3{0, -0.5f, 1}), 1e-6f,
                    "coat mapped");
    }
}
