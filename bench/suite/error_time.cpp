// Error against time, what a user waits for: each bench scene and each Mitsuba reference
// scene rendered for a series of sample counts by each engine with each sampler, the relative
// MSE against a converged reference over the seconds the render took. Also the error of the
// images averaged over aligned 2 x 2 squares of pixels, where blue-noise error (zsobol's)
// cancels.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sections.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

namespace {

// The image averaged over aligned 2 x 2 squares (a last odd row or column left out).
Image squares(const Image& a) {
    Image out;
    out.width = a.width / 2;
    out.height = a.height / 2;
    out.pixels.resize(size_t(out.width) * out.height);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x) {
            Color sum(0.0f);
            for (int dy = 0; dy < 2; ++dy)
                for (int dx = 0; dx < 2; ++dx)
                    sum += a.pixels[size_t(2 * y + dy) * a.width + (2 * x + dx)];
            out.pixels[size_t(y) * out.width + x] = sum * 0.25f;
        }
    return out;
}

// Each engine and sampler at `counts` samples per pixel, `seeds` seeds each, against `ref`;
// rows one line (engine, sampler) at a time.
void measure(const std::string& name,
             const Scene& scene,
             const Bvh& bvh,
             RenderRequest cfg,
             const Image& ref,
             const std::vector<int>& counts,
             int seeds,
             Results& r) {
    const Image ref_squares = squares(ref);
    // Counts in the outer loop, the engines and samplers inside it, so that the machine's
    // drift falls on all alike.
    struct Point {
        Engine engine;
        SamplerKind sampler;
        int spp;
        double seconds, mse, mse_squares;
    };
    std::vector<Point> points;
    for (int spp : counts)
        for (Engine engine : {Engine::Megakernel, Engine::Wavefront})
            for (SamplerKind sampler :
                 {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol}) {
                double seconds = 0, mse = 0, mse_squares = 0;
                for (int seed = 1; seed <= seeds; ++seed) {
                    cfg.spp = spp;
                    cfg.seed = uint64_t(seed);
                    cfg.sampler = sampler;
                    Image img;
                    seconds += render_once(scene, bvh, cfg, engine, &img).seconds;
                    mse += relative_mse(img, ref);
                    mse_squares += relative_mse(squares(img), ref_squares);
                }
                points.push_back(
                    {engine, sampler, spp, seconds / seeds, mse / seeds, mse_squares / seeds});
            }
    std::stable_sort(points.begin(), points.end(), [](const Point& a, const Point& b) {
        return std::pair(a.engine, a.sampler) < std::pair(b.engine, b.sampler);
    });
    for (const Point& p : points)
        r.row("error_time", {name, to_string(p.engine), to_string(p.sampler), p.spp, p.seconds,
                             p.mse, p.mse_squares});
    std::printf("error_time %s done\n", name.c_str());
    std::fflush(stdout);
}

}  // namespace

void bench_error_time(const Options& o, Results& r) {
    r.table("error_time",
            {"scene", "engine", "sampler", "spp", "seconds", "rel_mse", "rel_mse_2x2"});
    const int seeds = o.quick ? 1 : 2;
    struct Case {
        const char* scene;
        int w, h;
    };
    // The bench scenes, at a quarter of the engines section's sides, against 1,024-spp
    // renders of their own with other random numbers.
    const Case cases[] = {
        {"cornell", 96, 96},        {"everything", 96, 96},     {"bunny", 96, 96},
        {"dragon", 96, 96},         {"veach-mis", 128, 96},     {"materials", 128, 64},
        {"dragon-envmap", 128, 96}, {"cornell-glass", 96, 96},  {"cornell-mirror", 96, 96},
        {"cornell-smoke", 96, 96},  {"cornell-mcguire", 96, 96}};
    for (const Case& c : cases) {
        if (!o.wants(c.scene)) continue;
        Scene scene = load_scene(o.scenes / (std::string(c.scene) + ".json"));
        Bvh bvh = Bvh::build(scene);
        RenderRequest cfg;
        cfg.width = o.quick ? 8 : c.w;
        cfg.height = o.quick ? 8 : c.h;
        cfg.estimator.max_depth = scene.render.max_depth;
        cfg.spp = o.quick ? 4 : 1024;
        cfg.seed = 12345;
        cfg.sampler = SamplerKind::Sobol;
        Image ref;
        render_once(scene, bvh, cfg, Engine::Wavefront, &ref);
        measure(c.scene, scene, bvh, cfg, ref,
                o.quick ? std::vector<int>{1, 2} : std::vector<int>{1, 2, 4, 8, 16, 32}, seeds, r);
    }
    // Mitsuba 3's regression scenes of the reference tests, at their own sizes (48 x 48 to
    // 64 x 64, so more samples), against Mitsuba's converged images: no bench scene filter.
    if (!o.only.empty()) return;
    struct Reference {
        const char* name;
        const char* scene;  // under tests/reference-images/mitsuba3/tests/scenes/
        const char* image;
    };
    const Reference references[] = {
        {"mitsuba-pointlight", "bsdf_spheres/test_pointlight_path.xml",
         "bsdf_spheres/refs/test_pointlight_ref_rgb.exr"},
        {"mitsuba-arealight", "bsdf_spheres/test_arealight_path.xml",
         "bsdf_spheres/refs/test_arealight_ref_rgb.exr"},
        {"mitsuba-envmap", "bsdf_spheres/test_envmap_path.xml",
         "bsdf_spheres/refs/test_envmap_ref_rgb.exr"},
        {"mitsuba-roughdielectric", "bsdf_spheres/test_roughdielectric_path.xml",
         "bsdf_spheres/refs/test_roughdielectric_ref_rgb.exr"},
        {"mitsuba-roughplastic", "bsdf_spheres/test_roughplastic_linear_path.xml",
         "bsdf_spheres/refs/test_roughplastic_linear_ref_rgb.exr"},
        {"mitsuba-normalmap-conductor", "bsdf_spheres/test_normalmap_roughconductor_path.xml",
         "bsdf_spheres/refs/test_normalmap_roughconductor_ref_rgb.exr"},
        {"mitsuba-instancing", "instancing/test_instancing_path.xml",
         "instancing/refs/test_instancing_ref_rgb.exr"},
        {"mitsuba-media-dielectric", "participating_media/test_homo_dielectric_envmap_volpath.xml",
         "participating_media/refs/test_homo_dielectric_envmap_ref_rgb.exr"},
        {"mitsuba-media-null", "participating_media/test_homo_null_envmap_volpath.xml",
         "participating_media/refs/test_homo_null_envmap_ref_rgb.exr"},
        {"mitsuba-spot-texture", "spot_light/test_spot_direct.xml",
         "spot_light/refs/test_spot_ref_rgb.exr"}};
    const std::filesystem::path dir =
        std::filesystem::path(WAVETRACE_REFERENCE_IMAGES_DIR) / "mitsuba3/tests/scenes";
    for (const Reference& c : references) {
        Scene scene = load_scene(dir / c.scene);
        Bvh bvh = Bvh::build(scene);
        const ImageData data = read_image(dir / c.image);
        Image ref(data.width, data.height);
        ref.pixels = data.texels;
        RenderRequest cfg;
        cfg.width = data.width;
        cfg.height = data.height;
        cfg.estimator.max_depth = scene.render.max_depth;
        measure(c.name, scene, bvh, cfg, ref,
                o.quick ? std::vector<int>{1, 2} : std::vector<int>{4, 8, 16, 32, 64, 128, 256},
                seeds, r);
    }
}

}  // namespace wavetrace::bench
