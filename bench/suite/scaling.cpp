// Both engines on 1 .. N threads over the five bench scenes: throughput speed-up over one
// thread, parallel efficiency, and the wavefront/megakernel ratio at each thread count (the
// issue's 16-thread check: efficiency ≥ 90% and the ratio kept). The sample count grows with the
// threads (16 spp per two threads) so that every render lasts about as long: a render of a
// fixed size would shrink to a tenth of a second at 16 threads, where starting and draining
// the threads weigh on the figure.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstdio>

#include "sections.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

namespace {

// 1, 2, 4, 8, then steps of 4 up to max (and max itself): enough points for a curve at a
// fraction of the time of every count.
std::vector<int> thread_counts(int max) {
    std::vector<int> t;
    for (int n = 1; n <= max; n = n < 8 ? n * 2 : n + 4) t.push_back(n);
    if (t.back() != max) t.push_back(max);
    return t;
}

}  // namespace

void bench_scaling(const Options& o, Results& r) {
    r.table("scaling", {"scene", "engine", "threads", "spp", "mpaths", "speedup", "efficiency",
                        "wavefront_over_megakernel"});
    const int max_threads =
        o.max_threads > 0 ? o.max_threads : tbb::this_task_arena::max_concurrency();
    for (const char* name : {"cornell", "everything", "bunny", "dragon", "veach-mis"}) {
        if (!o.wants(name)) continue;
        Scene scene = load_scene(o.scenes / (std::string(name) + ".json"));
        Bvh bvh = Bvh::build(scene);
        RenderConfig cfg;
        cfg.width = o.quick ? 16 : 320;
        cfg.height = o.quick ? 16 : 320;
        cfg.seed = 1;
        cfg.max_depth = scene.render.max_depth;
        double base_mk = 0, base_wf = 0;  // Mpaths/s at one thread
        for (int t : thread_counts(max_threads)) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, t);
            cfg.spp = o.quick ? 1 : 16 * ((t + 1) / 2);
            // Interleaved (A B A B ...), medians, to damp the noise of a shared machine.
            std::vector<double> mk, wf, ratio;
            for (int rep = 0; rep < (o.quick ? 1 : kRepetitions); ++rep) {
                RenderStats a, b;
                render_megakernel(scene, bvh, cfg, &a);
                render_wavefront(scene, bvh, cfg, {}, &b);
                mk.push_back(a.paths / a.seconds * 1e-6);
                wf.push_back(b.paths / b.seconds * 1e-6);
                ratio.push_back(a.seconds / b.seconds);
            }
            const double mk_p = spread(mk).median, wf_p = spread(wf).median;
            const double q = spread(ratio).median;
            if (t == 1) {
                base_mk = mk_p;
                base_wf = wf_p;
            }
            const double mk_up = mk_p / base_mk, wf_up = wf_p / base_wf;
            r.row("scaling", {name, "megakernel", t, cfg.spp, mk_p, mk_up, mk_up / t, q});
            r.row("scaling", {name, "wavefront", t, cfg.spp, wf_p, wf_up, wf_up / t, q});
            std::printf(
                "scaling %-10s %2d threads %3d spp: speed-up megakernel %5.2fx, wavefront %5.2fx "
                "(efficiency %.2f, %.2f); wavefront/megakernel %.2f\n",
                name, t, cfg.spp, mk_up, wf_up, mk_up / t, wf_up / t, q);
            std::fflush(stdout);
        }
    }
}

}  // namespace wavetrace::bench
