// Relative MSE against a long reference render versus render time, per strategy;
// efficiency = 1 / (rMSE x time) (higher is better).
#include <cstdio>

#include "sections.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

void bench_convergence(const Options& o, Results& r) {
    r.table("convergence", {"scene", "strategy", "spp", "seconds", "rel_mse", "efficiency"});
    struct Case {
        const char* scene;
        int w, h, max_depth;
    };
    for (const Case& c : {Case{"cornell", 96, 96, 8}, Case{"veach-mis", 128, 96, 8}}) {
        Scene scene = load_scene(o.scenes / (std::string(c.scene) + ".json"));
        Bvh bvh = Bvh::build(scene);
        RenderRequest cfg;
        cfg.width = o.quick ? 8 : c.w;
        cfg.height = o.quick ? 8 : c.h;
        cfg.estimator.max_depth = c.max_depth;
        cfg.estimator.strategy = Strategy::Mis;
        cfg.spp = o.quick ? 4 : 4096;
        cfg.seed = 12345;  // the reference uses other random numbers than the renders it judges
        Image ref;
        render_once(scene, bvh, cfg, Engine::Wavefront, &ref);
        cfg.seed = 1;
        for (Strategy st :
             {Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Nee, Strategy::Mis})
            for (int spp : {1, 4, 16, 64, 256}) {
                if (o.quick && spp > 4) break;
                cfg.estimator.strategy = st;
                cfg.spp = spp;
                Image img;
                const RenderStats stats = render_once(scene, bvh, cfg, Engine::Wavefront, &img);
                double rmse = relative_mse(img, ref);
                r.row("convergence", {c.scene, to_string(st), spp, stats.seconds, rmse,
                                      1.0 / (rmse * stats.seconds)});
            }
        std::printf("convergence %s done\n", c.scene);
        std::fflush(stdout);
    }
}

}  // namespace wavetrace::bench
