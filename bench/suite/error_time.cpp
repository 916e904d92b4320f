// Error against time, what a user waits for: each bench scene rendered for a series of sample
// counts by each engine with each sampler, the relative MSE against a converged reference over
// the seconds the render took. Also the error of the images averaged over aligned 2 x 2
// squares of pixels, where blue-noise error (zsobol's) cancels.
#include <algorithm>
#include <cstdio>
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

}  // namespace

void bench_error_time(const Options& o, Results& r) {
    r.table("error_time",
            {"scene", "engine", "sampler", "spp", "seconds", "rel_mse", "rel_mse_2x2"});
    struct Case {
        const char* scene;
        int w, h;
    };
    // A quarter of the engines section's sides: the 1,024-spp references stay affordable.
    const Case cases[] = {
        {"cornell", 96, 96},        {"everything", 96, 96},     {"bunny", 96, 96},
        {"dragon", 96, 96},         {"veach-mis", 128, 96},     {"materials", 128, 64},
        {"dragon-envmap", 128, 96}, {"cornell-glass", 96, 96},  {"cornell-mirror", 96, 96},
        {"cornell-smoke", 96, 96},  {"cornell-mcguire", 96, 96}};
    const int seeds = o.quick ? 1 : 2;
    for (const Case& c : cases) {
        if (!o.wants(c.scene)) continue;
        Scene scene = load_scene(o.scenes / (std::string(c.scene) + ".json"));
        Bvh bvh = Bvh::build(scene);
        RenderRequest cfg;
        cfg.width = o.quick ? 8 : c.w;
        cfg.height = o.quick ? 8 : c.h;
        cfg.estimator.max_depth = scene.render.max_depth;
        cfg.spp = o.quick ? 4 : 1024;
        cfg.seed = 12345;  // the reference draws other numbers than the renders it judges
        cfg.sampler = SamplerKind::Sobol;
        Image ref;
        render_once(scene, bvh, cfg, Engine::Wavefront, &ref);
        const Image ref_squares = squares(ref);
        // Counts in the outer loop, the engines and samplers inside it, so that the machine's
        // drift falls on all alike; the rows then go out one line (engine, sampler) at a time.
        struct Point {
            Engine engine;
            SamplerKind sampler;
            int spp;
            double seconds, mse, mse_squares;
        };
        std::vector<Point> points;
        for (int spp = 1; spp <= (o.quick ? 2 : 32); spp *= 2)
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
            r.row("error_time", {c.scene, to_string(p.engine), to_string(p.sampler), p.spp,
                                 p.seconds, p.mse, p.mse_squares});
        std::printf("error_time %s done\n", c.scene);
        std::fflush(stdout);
    }
}

}  // namespace wavetrace::bench
