// Both engines on 1, 2, ... N threads: speed-up over one thread and parallel efficiency.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstdio>

#include "sections.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

void bench_scaling(const Options& o, Results& r) {
    r.table("scaling", {"scene", "engine", "threads", "seconds", "speedup", "efficiency"});
    const int max_threads =
        o.max_threads > 0 ? o.max_threads : tbb::this_task_arena::max_concurrency();
    for (const char* name : {"cornell", "dragon"}) {
        Scene scene = load_scene(o.scenes / (std::string(name) + ".json"));
        Bvh bvh = Bvh::build(scene);
        RenderConfig cfg;
        cfg.width = o.quick ? 16 : 256;
        cfg.height = o.quick ? 16 : 256;
        cfg.spp = o.quick ? 1 : 8;
        cfg.seed = 1;
        cfg.max_depth = scene.render.max_depth;
        double base_mk = 0, base_wf = 0;
        for (int t = 1; t <= max_threads; ++t) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, t);
            // Interleaved, best of two each, to damp the noise of a shared machine.
            double mk = 1e30, wf = 1e30;
            for (int rep = 0; rep < (o.quick ? 1 : 2); ++rep) {
                RenderStats a, b;
                render_megakernel(scene, bvh, cfg, &a);
                render_wavefront(scene, bvh, cfg, {}, &b);
                mk = std::min(mk, a.seconds);
                wf = std::min(wf, b.seconds);
            }
            if (t == 1) {
                base_mk = mk;
                base_wf = wf;
            }
            r.row("scaling", {name, "megakernel", t, mk, base_mk / mk, base_mk / mk / t});
            r.row("scaling", {name, "wavefront", t, wf, base_wf / wf, base_wf / wf / t});
            std::printf("scaling %-8s %2d threads: megakernel %.2fx, wavefront %.2fx\n", name, t,
                        base_mk / mk, base_wf / wf);
            std::fflush(stdout);
        }
    }
}

}  // namespace wavetrace::bench
