// The wavefront engine against the megakernel (same estimator, same random numbers: the same
// image up to rounding), and its determinism.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cmath>
#include <filesystem>
#include <numeric>
#include <string>

#include "engines/wavefront.h"
#include "render_film.h"
#include "test_paths.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

RenderRequest config(Strategy st, int w, int h, int spp, uint64_t seed = 11) {
    RenderRequest c;
    c.width = w;
    c.height = h;
    c.spp = spp;
    c.seed = seed;
    c.estimator.strategy = st;
    return c;
}

// The engines' images side by side: pixel channels outside 1e-4 relative (and 1e-6 absolute),
// the worst relative difference and where, and the image means.
struct Agreement {
    size_t outside = 0, values = 0;
    double worst = 0, sum_mk = 0, sum_wv = 0;
    int worst_pixel = -1;
    double mean_rel() const { return std::fabs(sum_mk - sum_wv) / std::max(sum_mk, 1e-30); }
};

Agreement compare_engines(const Image& mk, const Image& wv) {
    Agreement r;
    for (size_t i = 0; i < mk.pixels.size(); ++i)
        for (int k = 0; k < 3; ++k, ++r.values) {
            const double a = mk.pixels[i][k], b = wv.pixels[i][k];
            r.sum_mk += a;
            r.sum_wv += b;
            const double diff = std::fabs(a - b);
            if (diff > 1e-6 && diff > 1e-4 * std::fabs(a)) ++r.outside;
            const double rel = diff / std::max(std::fabs(a), 1e-6);
            if (rel > r.worst) {
                r.worst = rel;
                r.worst_pixel = static_cast<int>(i);
            }
        }
    return r;
}

// Rounding apart, the same image: 99.9% of pixel channels within the bound, means within 1e-5.
void expect_same_image(const Agreement& r, const std::string& what) {
    EXPECT_LE(r.outside, r.values / 1000) << what;
    EXPECT_LE(r.mean_rel(), 1e-5) << what;
}

}  // namespace

// Every shipped scene, every strategy and sampler, 4 spp: per pixel within 1e-4 relative (or
// 1e-6 absolute) in at least 99.9% of pixel channels, image means within 1e-5 relative.
TEST(Wavefront, EqualsTheMegakernel) {
    for (const char* name :
         {"cornell", "cornell-glass", "cornell-mirror", "cornell-smoke", "cornell-mcguire",
          "everything", "bunny", "dragon", "dragon-envmap", "veach-mis", "materials"}) {
        Scene scene = load_scene(scene_path(name));
        Bvh bvh = Bvh::build(scene);
        for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol})
        for (Strategy st :
             {Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Nee, Strategy::Mis}) {
            RenderRequest c = config(st, 40, 40, 4);
            c.sampler = kind;
            WavefrontOptions wf;
            wf.wave_size = 700;  // several waves, the last one partial
            Image mk = megakernel_film(scene, bvh, c).mean();
            Image wv = wavefront_film(scene, bvh, c, wf).mean();
            const Agreement r = compare_engines(mk, wv);
            std::printf(
                "wavefront-vs-megakernel %-14s %-8s %-11s outside bound %zu/%zu, worst "
                "relative %.2e (pixel %d), image means %.2e relative\n",
                name, to_string(st), to_string(kind), r.outside, r.values, r.worst, r.worst_pixel,
                r.mean_rel());
            expect_same_image(r, std::string(name) + " " + to_string(st) + " " + to_string(kind));
        }
    }
}

// Mitsuba 3's regression scenes, read from their XML files (the `reference` tests hold the
// wavefront to Mitsuba's images at 1,024 spp and more): the megakernel renders the wavefront's
// image of each, under the same bounds as the shipped scenes, so that it matches Mitsuba's
// references too without rendering them again at their sample counts.
TEST(Wavefront, EqualsTheMegakernelOnMitsubasScenes) {
    const std::filesystem::path dir =
        std::filesystem::path(WAVETRACE_REFERENCE_DIR) / "mitsuba3/tests/scenes";
    for (const char* name : {"infinite_mirrors/scene_path.xml",
                             "instancing/test_instancing_path.xml",
                             "participating_media/test_homo_null_envmap_volpath.xml",
                             "participating_media/test_homo_dielectric_envmap_volpath.xml",
                             "participating_media/test_homo_area_light_volpath.xml",
                             "participating_media/test_homo_emitter_inside_medium_volpath.xml",
                             "participating_media/test_homo_obj_inside_medium_volpath.xml",
                             "participating_media/test_homo_spectral_sigmat_volpathmis.xml",
                             "participating_media/test_homo_roughdielectric_spot_volpath.xml",
                             "participating_media/test_hetero_sigmat_albedo_volpath.xml",
                             "participating_media/test_hetero_spectral_sigmat_volpathmis.xml",
                             "bsdf_spheres/test_pointlight_path.xml",
                             "bsdf_spheres/test_arealight_path.xml",
                             "bsdf_spheres/test_constant_path.xml",
                             "bsdf_spheres/test_envmap_path.xml",
                             "bsdf_spheres/test_textured_diffuse_path.xml",
                             "bsdf_spheres/test_roughdielectric_path.xml",
                             "bsdf_spheres/test_roughplastic_linear_path.xml",
                             "bsdf_spheres/test_roughplastic_nonlinear_path.xml",
                             "bsdf_spheres/test_textured_roughconductor_path.xml",
                             "bsdf_spheres/test_bumpmap_path.xml",
                             "bsdf_spheres/test_normalmap_path.xml",
                             "bsdf_spheres/test_normalmap_roughconductor_path.xml",
                             "bsdf_spheres/test_texturedprincipled2_path.xml",
                             "bsdf_spheres/test_texturedprincipledthin_path.xml",
                             "floating_sphere/test_directional_direct.xml",
                             "spot_light/test_spot_direct.xml",
                             "orthographic_sensor/test_orthographic_path.xml",
                             "projector/test_projector_textured_direct.xml"}) {
        SCOPED_TRACE(name);
        Scene scene = load_scene(dir / name);
        Bvh bvh = Bvh::build(scene);
        RenderRequest c = config(Strategy::Mis, scene.render.width, scene.render.height, 16, 1);
        c.sampler = scene.render.sampler;
        c.estimator.max_depth = scene.render.max_depth;
        const Image mk = megakernel_film(scene, bvh, c).mean();
        const Image wv = wavefront_film(scene, bvh, c).mean();
        const Agreement r = compare_engines(mk, wv);
        std::printf(
            "wavefront-vs-megakernel %s: outside bound %zu/%zu, image means %.2e relative\n", name,
            r.outside, r.values, r.mean_rel());
        expect_same_image(r, name);
    }
}

// Where no ray can find a light (point lights only, a black background), the ray that would end
// a path at max_depth finds nothing and is not traced (ray_may_bring_light): at max_depth 2 a
// floor under a point light costs each engine its camera ray and one shadow ray per path. With
// an area light in the scene that ray is traced again, for the emission it may find.
TEST(Wavefront, NoRayEndsAPathWhereNoRayFindsLight) {
    Scene s;
    Material floor;
    floor.kind = MaterialKind::Lambertian;
    floor.albedo = s.add_solid(Color(0.5f));
    s.add_quad({{-50, 0, -50}, {0, 0, 100}, {100, 0, 0}, s.add_material(floor), kNone});
    s.camera.look_from = {0, 3, -3};
    s.camera.look_at = {0, 0, 0};
    s.camera.vfov = 20;  // every camera ray meets the floor
    Light point;
    point.position = {0, 2, 0};
    point.intensity = Color(5.0f);
    s.lights.push_back(point);
    RenderRequest c = config(Strategy::Mis, 16, 16, 4);
    c.estimator.max_depth = 2;
    for (const bool lamp : {false, true}) {
        if (lamp) {  // facing the floor
            Material m;
            m.kind = MaterialKind::DiffuseLight;
            m.emission = s.add_solid(Color(2.0f));
            s.add_quad({{-1, 4, -1}, {2, 0, 0}, {0, 0, 2}, s.add_material(m), kNone});
        }
        const Bvh bvh = Bvh::build(s);
        RenderStats mk, wv;
        megakernel_film(s, bvh, c, &mk);
        wavefront_film(s, bvh, c, {}, &wv);
        ASSERT_EQ(mk.paths, 16u * 16u * 4u);
        for (const RenderStats& st : {mk, wv})
            EXPECT_EQ(st.rays, (lamp ? 3 : 2) * st.paths) << lamp;
    }
}

TEST(Wavefront, BitIdenticalForAnyThreadCountAndWaveSize) {
    Scene scene = load_scene(scene_path("cornell-smoke"));
    Bvh bvh = Bvh::build(scene);
    for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol}) {
    RenderRequest c = config(Strategy::Mis, 37, 23, 5);  // 851 pixels
    c.sampler = kind;
    // Fewer threads than the machine has through a global_control limit (as --threads does),
    // more through an arena of that many (oversubscribed here, but every thread takes waves).
    auto render = [&](int threads, size_t wave, bool sort, Schedule schedule) {
        WavefrontOptions wf;
        wf.wave_size = wave;
        wf.sort_by_material = sort;
        wf.schedule = schedule;
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        tbb::task_arena arena(threads);
        return arena.execute([&] { return wavefront_film(scene, bvh, c, wf).mean(); });
    };
    constexpr Schedule resident = Schedule::Resident, stage = Schedule::Stage;
    Image ref = render(1, 851, false, resident);
    struct Run {
        int threads;
        size_t wave;
        bool sort;
        Schedule schedule;
    };
    for (Run r :
         {Run{2, 851, false, resident}, Run{7, 851, false, resident}, Run{2, 256, false, resident},
          Run{7, 300, false, resident},  // 300 divides nothing
          Run{1, 64, false, resident}, Run{1, 851, true, resident}, Run{7, 300, true, resident},
          // one wave of 851 paths, and waves of 7 x 300 = 2100 > 851, 2 x 64 = 128
          Run{1, 851, false, stage}, Run{7, 300, false, stage}, Run{2, 64, false, stage},
          Run{2, 64, true, stage}}) {
        Image img = render(r.threads, r.wave, r.sort, r.schedule);
        for (size_t i = 0; i < ref.pixels.size(); ++i)
            ASSERT_EQ(ref.pixels[i], img.pixels[i])
                << "threads " << r.threads << " wave " << r.wave << " sort " << r.sort
                << " schedule " << to_string(r.schedule) << " sampler " << to_string(kind)
                << " pixel " << i;
    }
    }
}

// The two schedules run the same kernels on the same paths: every shipped scene and strategy
// gives the same image, bit for bit, with waves of several chunks of the stage schedule
// (kStageChunk) and a partial last one; and without media or thin sheets the same rays.
// (Where shadow rays walk, those from one primitive go as packets of eight consecutive queue
// entries, which the two schedules' queues group differently: the count of tests differs, not
// their result.)
TEST(Wavefront, StageScheduleEqualsResidentBitForBit) {
    for (const char* name : {"cornell", "cornell-glass", "cornell-smoke", "everything", "dragon",
                             "veach-mis", "materials"}) {
        Scene scene = load_scene(scene_path(name));
        Bvh bvh = Bvh::build(scene);
        for (Strategy st :
             {Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Nee, Strategy::Mis}) {
            RenderRequest c = config(st, 61, 47, 2);  // 2,867 pixels
            // Two of the cases draw from the Sobol sampler, one from zsobol.
            if (st == Strategy::Nee || st == Strategy::Light) c.sampler = SamplerKind::Sobol;
            if (st == Strategy::Mis) c.sampler = SamplerKind::ZSobol;
            WavefrontOptions resident, stage;
            resident.wave_size = stage.wave_size = 700;
            stage.schedule = Schedule::Stage;
            RenderStats rs, ss;
            const Image a = wavefront_film(scene, bvh, c, resident, &rs).mean();
            const Image b = wavefront_film(scene, bvh, c, stage, &ss).mean();
            if (!shadows_walk(scene)) {
                EXPECT_EQ(rs.rays, ss.rays) << name << " " << to_string(st);
            }
            for (size_t i = 0; i < a.pixels.size(); ++i)
                ASSERT_EQ(a.pixels[i], b.pixels[i])
                    << name << " " << to_string(st) << " pixel " << i;
        }
    }
}

// The guided schedule: the waves cover the pixels once, in order; none is larger than
// wave_size or 1/64 of the image (but 32 pixels), none smaller than 128 but where less is left
// or allowed; they shrink, and each takes at most a share 1 / (2 threads) of what is left, so
// the last ones started are small.
TEST(Wavefront, WavesCoverThePixelsOnceAndShrinkTowardsTheEnd) {
    for (size_t pixels :
         {size_t(1), size_t(100), size_t(851), size_t(320 * 320), size_t(1920 * 1080)})
        for (size_t threads : {1, 2, 7, 16})
            for (size_t wave_size : {64, 300, 4096}) {
                WavefrontOptions wf;
                wf.wave_size = wave_size;
                const std::vector<WaveRange> waves = wavefront_waves(pixels, threads, wf);
                const std::string at = "pixels " + std::to_string(pixels) + " threads " +
                                       std::to_string(threads) + " wave " +
                                       std::to_string(wave_size);
                ASSERT_FALSE(waves.empty()) << at;
                EXPECT_EQ(wavefront_wave_size(pixels, threads, wf), waves.front().n) << at;
                const size_t most =
                    std::min({wave_size, pixels, std::max<size_t>(pixels / 64, 32)});
                EXPECT_EQ(wavefront_wave_pixels(pixels, wf), most) << at;
                size_t first = 0;
                for (size_t w = 0; w < waves.size(); ++w) {
                    const size_t left = pixels - first;
                    ASSERT_EQ(waves[w].first, first) << at << " wave " << w;
                    ASSERT_GE(waves[w].n, std::min({size_t(128), most, left})) << at;
                    ASSERT_LE(waves[w].n, most) << at;
                    ASSERT_LE(waves[w].n,
                              std::max<size_t>(128, (left + 2 * threads - 1) / (2 * threads)))
                        << at << " wave " << w;
                    if (w > 0) {
                        ASSERT_LE(waves[w].n, waves[w - 1].n) << at;
                    }
                    first += waves[w].n;
                }
                EXPECT_EQ(first, pixels) << at;
            }
    // A 320² image on 16 threads starts with waves of 1,600 pixels (1/64 of it) and two samples
    // of each, 3,200 paths, not 100 (102,400 / 1,024); a 48² image at 1,024 spp with waves of
    // 36 pixels, 113 samples of each.
    const WavefrontOptions wf;
    EXPECT_EQ(wavefront_wave_size(320 * 320, 16, wf), size_t(1600));
    const size_t paths = wavefront_wave_paths(1600, 320 * 320, 16, wf.wave_size);
    EXPECT_EQ(wave_samples_per_pixel(1600, paths, 16) * 1600, 3200u);
    EXPECT_EQ(wavefront_wave_size(48 * 48, 2, wf), size_t(36));
    EXPECT_EQ(
        wave_samples_per_pixel(36, wavefront_wave_paths(36, 48 * 48, 1024, wf.wave_size), 1024),
        4096u / 36);
}

// An anisotropic conductor's roughness runs along dp/du: the light_sample kernel rebuilds that
// frame from the angle its queue keeps, not from the normal alone (which once gave the
// wavefront 1% more light than the megakernel here). Its roughness from textures (a checker
// of alpha_u against a number alpha_v): the light sample evaluates the vertex's values.
TEST(Wavefront, AnisotropicSurfacesEqualTheMegakernel) {
    for (bool textured : {false, true}) {
        Scene scene;
        Material brushed;
        brushed.kind = MaterialKind::Conductor;
        brushed.albedo = scene.add_solid(Color(1.0f));
        brushed.eta = {0.2f, 0.4f, 1.4f};
        brushed.k = {3.5f, 2.4f, 1.8f};
        brushed.alpha_u = 0.05f;
        brushed.alpha_v = 0.4f;
        if (textured) {
            Texture checker;
            checker.kind = TextureKind::UvChecker;
            checker.scale = 0.1f;
            checker.even = scene.add_solid(Color(0.05f));
            checker.odd = scene.add_solid(Color(0.6f));
            brushed.alpha_u = 1.0f;
            brushed.alpha_u_texture = scene.add_texture(checker);
        }
        Material floor;
        floor.albedo = scene.add_solid(Color(0.5f));
        Material light;
        light.kind = MaterialKind::DiffuseLight;
        light.emission = scene.add_solid({6, 5, 4});
        scene.add_sphere({{0, 0, 0}, 1, scene.add_material(brushed), kNone});
        scene.add_quad({{-5, -1, -5}, {10, 0, 0}, {0, 0, 10}, scene.add_material(floor), kNone});
        scene.add_quad({{-1, 3, -1}, {2, 0, 0}, {0, 0, 2}, scene.add_material(light), kNone});
        scene.lights.push_back(Light::point({2, 3, -2}, Color(20.0f)));
        scene.background.radiance = Color(0.2f);
        scene.camera.look_from = {0, 1, -4};
        scene.camera.look_at = {0, 0, 0};
        Bvh bvh = Bvh::build(scene);
        for (Strategy st : {Strategy::Light, Strategy::Nee, Strategy::Mis}) {
            const RenderRequest c = config(st, 40, 40, 4);
            const Image mk = megakernel_film(scene, bvh, c).mean();
            const Image wv = wavefront_film(scene, bvh, c).mean();
            expect_same_image(compare_engines(mk, wv),
                              std::string(to_string(st)) + (textured ? " textured" : ""));
        }
    }
}

// Lambertian and rough metal surfaces of textured albedo (an image and a checker on quads, a
// noise and an image on spheres) are shaded in the wavefront's lanes, their albedo looked up
// after the block resolves the hit: the megakernel's image, as for every shipped scene. So is a
// metallic-roughness sphere whose coat's weight and roughness are textures, which the light
// samples look up again from the vertex's uv, and one whose transmission is a texture and whose
// coat has a normal map of its own over a normal-mapped base (the coat's normal travels in the
// light-sample queue).
TEST(Wavefront, TexturedSurfacesInLanesEqualTheMegakernel) {
    Scene scene;
    ImageData image;
    image.path = "synthetic";
    image.width = 4;
    image.height = 3;
    for (int k = 0; k < 12; ++k)
        image.texels.push_back(Color(0.1f + 0.07f * k, 0.8f - 0.05f * k, 0.3f + 0.02f * (k % 5)));
    Texture picture;
    picture.kind = TextureKind::Image;
    picture.image = scene.add_image(image);
    Texture checker;
    checker.kind = TextureKind::Checker;
    checker.scale = 0.3f;
    checker.even = scene.add_solid({0.8f, 0.2f, 0.2f});
    checker.odd = scene.add_solid({0.2f, 0.7f, 0.3f});
    Texture noise;
    noise.kind = TextureKind::Noise;
    noise.color = Color(0.9f);
    noise.scale = 4.0f;
    auto lambertian = [&](const Texture& t) {
        Material m;
        m.albedo = scene.add_texture(t);
        return scene.add_material(m);
    };
    const MaterialId floor = lambertian(picture), wall = lambertian(checker),
                     marble = lambertian(noise);
    Material brushed;
    brushed.kind = MaterialKind::Metal;
    brushed.albedo = scene.add_texture(picture);
    brushed.roughness = 0.4f;
    const MaterialId metal = scene.add_material(brushed);
    Material coated;
    coated.kind = MaterialKind::MetallicRoughness;
    coated.albedo = scene.add_solid({0.6f, 0.1f, 0.1f});
    coated.metallic = 0.0f;
    coated.roughness = 0.5f;
    coated.clearcoat = 1.0f;
    coated.clearcoat_roughness = 0.6f;
    coated.clearcoat_map = scene.add_texture(checker);
    coated.clearcoat_roughness_map = scene.add_texture(picture);
    const MaterialId car_paint = scene.add_material(coated);
    Material ribbed = coated;
    ribbed.transmission = 0.7f;
    ribbed.transmission_map = scene.add_texture(checker);
    ribbed.normal_map = scene.add_solid({0.7f, 0.5f, 1.0f});
    ribbed.clearcoat_normal_map = scene.add_solid({0.5f, 0.25f, 1.0f});
    ribbed.clearcoat_roughness = 0.3f;
    const MaterialId ribbed_paint = scene.add_material(ribbed);
    Material light;
    light.kind = MaterialKind::DiffuseLight;
    light.emission = scene.add_solid({6, 5, 4});
    const MaterialId lamp = scene.add_material(light);
    scene.add_quad({{-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, floor, kNone});
    scene.add_quad({{-2, 0, -2}, {4, 0, 0}, {0, 3, 0}, wall, kNone});
    scene.add_quad({{-0.5f, 2.5f, -0.5f}, {1, 0, 0}, {0, 0, 1}, lamp, kNone});
    scene.add_sphere({{-0.6f, 0.5f, 0}, 0.5f, marble, kNone});
    scene.add_sphere({{0.7f, 0.6f, 0.3f}, 0.6f, metal, kNone});
    scene.add_sphere({{0.1f, 0.35f, 1.0f}, 0.35f, car_paint, kNone});
    scene.add_sphere({{-1.0f, 0.3f, 1.1f}, 0.3f, ribbed_paint, kNone});
    scene.camera.look_from = {0, 1.2f, 4};
    scene.camera.look_at = {0, 0.7f, 0};
    Bvh bvh = Bvh::build(scene);
    for (Strategy st : {Strategy::Bsdf, Strategy::Nee, Strategy::Mis}) {
        RenderRequest c = config(st, 48, 36, 4);
        Image mk = megakernel_film(scene, bvh, c).mean();
        Image wv = wavefront_film(scene, bvh, c).mean();
        const Agreement r = compare_engines(mk, wv);
        EXPECT_GT(r.sum_mk, 0.0) << to_string(st);
        expect_same_image(r, to_string(st));
    }
}
