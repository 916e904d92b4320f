// Both engines on 1 .. N threads over the five bench scenes, the wavefront in both its schedules
// (resident: each thread carries its own wave through every kernel; stage: each kernel one
// parallel loop over all waves): throughput speed-up over one thread, parallel efficiency, and
// the ratio over the megakernel at each thread count (the `stage` rows' ratio is the stage
// schedule's; their renders-alone columns are the resident wavefront's, whose one-thread
// renders are the same kernels). The sample count grows with the
// threads (16 spp per two threads) so that every render lasts about as long: a render of a
// fixed size would shrink to a tenth of a second at 16 threads, where starting and draining
// the threads weigh on the figure.
//
// Beside each engine's speed-up, the machine's own: t one-thread renders of the same engine run
// at once, each in its own thread and task arena of one, sharing nothing but the scene (the
// t-thread render's spp / t each: 8 at even counts, so that between them they do its work).
// Timed until the last one ends, they are the simplest parallel renderer (a static split of
// the samples), and an engine's speed-up over theirs is what its own scheduling wins or loses;
// the sum of each one's own rate is what t busy cores give work that never synchronises
// (shared caches and memory bandwidth, clocks that fall as more cores run, neighbours),
// stragglers left out. Under both, the machine's ceiling for work that touches no memory:
// t threads each running the same chains of arithmetic, the sum of their own rates over one
// thread's (clocks that fall as more cores run, cores shared by two of the guest's threads or
// with another guest's).
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstdio>
#include <thread>

#include "sections.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

namespace {

// Powers of two up to max (and max itself): enough points for a curve at a fraction of the
// time of every count.
std::vector<int> thread_counts(int max) {
    std::vector<int> t;
    for (int n = 1; n <= max; n *= 2) t.push_back(n);
    if (t.back() != max) t.push_back(max);
    return t;
}

// Runs job(0), ..., job(threads - 1) at once, each on a thread of its own, and waits for all:
// the independent renders and the arithmetic ceiling below.
template <class Job>
void at_once(int threads, const Job& job) {
    std::vector<std::thread> workers;
    for (int i = 0; i < threads; ++i) workers.emplace_back(job, i);
    for (std::thread& w : workers) w.join();
}

// Mpaths/s of `threads` one-thread renders run at once, each with its own seed: all their
// paths over the time until the last one ends, and the sum of each one's own rate.
struct Independent {
    double until_last = 0;
    double own_rates = 0;
};

template <class Render>
Independent independent_mpaths(int threads, RenderRequest cfg, const Render& render) {
    std::vector<RenderStats> stats(threads);
    const auto start = std::chrono::steady_clock::now();
    at_once(threads, [&](int i) {
        RenderRequest own = cfg;
        own.seed += static_cast<uint64_t>(i);
        tbb::task_arena one(1);
        one.execute([&] { render(own, &stats[i]); });
    });
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    Independent r;
    for (const RenderStats& s : stats) {
        r.until_last += s.paths / seconds * 1e-6;
        r.own_rates += s.paths / s.seconds * 1e-6;
    }
    return r;
}

// One of the independent renders' figures over the one-thread rate `base`, median over the
// repetitions (none at one thread, where a render alone is the baseline).
double speedup_of(const std::vector<Independent>& runs, double Independent::*figure, double base) {
    if (runs.empty()) return 1;
    std::vector<double> v;
    for (const Independent& run : runs) v.push_back(run.*figure);
    return spread(v).median / base;
}

// Iterations a second of 24 independent chains of multiply-adds in registers: more independent
// operations than the pipes' latency needs, so the core's arithmetic throughput bounds it (a
// core shared by two threads halves each one's rate), and no memory, so nothing else does:
// the rate follows only the core's clock and whatever shares the core.
double arithmetic_rate(uint64_t iterations) {
    double x[24];
    for (int i = 0; i < 24; ++i) x[i] = i + 1;
    const auto start = std::chrono::steady_clock::now();
    for (uint64_t i = 0; i < iterations; ++i)
        for (double& v : x) v = v * 0.999999 + 1e-7;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    volatile double sink = 0;  // the chains' results are used, so they are computed
    for (double v : x) sink = sink + v;
    return double(iterations) / seconds;
}

// The sum of `threads` threads' own arithmetic rates, each thread's alone.
double arithmetic_rates(int threads, uint64_t iterations) {
    std::vector<double> rate(threads);
    at_once(threads, [&](int i) { rate[i] = arithmetic_rate(iterations); });
    double sum = 0;
    for (double r : rate) sum += r;
    return sum;
}

}  // namespace

void bench_scaling(const Options& o, Results& r) {
    r.table("scaling",
            {"scene", "engine", "threads", "spp", "mpaths", "speedup", "efficiency",
             "wavefront_over_megakernel", "independent_speedup", "speedup_over_independent",
             "independent_own_speedup", "arithmetic_speedup"});
    const int max_threads =
        o.max_threads > 0 ? o.max_threads : tbb::this_task_arena::max_concurrency();
    // The arithmetic ceiling at each count, medians of the repetitions, measured once for all
    // scenes (about 0.2 s a run on this project's machine).
    const std::vector<int> counts = thread_counts(max_threads);
    const uint64_t iterations = o.quick ? 100'000 : 50'000'000;
    std::vector<double> arithmetic;  // speed-up over one thread, per count
    for (int t : counts) {
        std::vector<double> runs;
        for (int rep = 0; rep < o.repetitions(); ++rep)
            runs.push_back(arithmetic_rates(t, iterations));
        arithmetic.push_back(spread(runs).median);
    }
    const double one_thread = arithmetic.front();
    for (size_t i = 0; i < counts.size(); ++i) {
        arithmetic[i] /= one_thread;
        std::printf("scaling arithmetic %2d threads: %5.2fx one thread's rate\n", counts[i],
                    arithmetic[i]);
    }
    for (const char* name : {"cornell", "everything", "bunny", "dragon", "veach-mis"}) {
        if (!o.wants(name)) continue;
        Scene scene = load_scene(o.scenes / (std::string(name) + ".json"));
        Bvh bvh = Bvh::build(scene);
        RenderRequest cfg;
        cfg.width = o.quick ? 16 : 320;
        cfg.height = o.quick ? 16 : 320;
        cfg.seed = 1;
        cfg.sampler = o.sampler;
        cfg.estimator.max_depth = scene.render.max_depth;
        const auto megakernel = [&](const RenderRequest& c, RenderStats* s) {
            *s = render_once(scene, bvh, c, Engine::Megakernel);
        };
        const auto wavefront = [&](const RenderRequest& c, RenderStats* s) {
            *s = render_once(scene, bvh, c, Engine::Wavefront);
        };
        double base_mk = 0, base_wf = 0, base_st = 0;  // Mpaths/s at one thread
        for (size_t c = 0; c < counts.size(); ++c) {
            const int t = counts[c];
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, t);
            cfg.spp = o.quick ? 1 : 16 * ((t + 1) / 2);
            RenderRequest each = cfg;
            each.spp = std::max(1, cfg.spp / t);
            RenderRequest staged = cfg;
            staged.wavefront.schedule = Schedule::Stage;
            // Interleaved (A B C A B C ...), medians, to damp the noise of a shared machine.
            std::vector<double> mk, wf, st, ratio, st_ratio;
            std::vector<Independent> mk_alone, wf_alone;
            for (int rep = 0; rep < o.repetitions(); ++rep) {
                RenderStats a, b, d;
                megakernel(cfg, &a);
                wavefront(cfg, &b);
                wavefront(staged, &d);
                mk.push_back(a.paths / a.seconds * 1e-6);
                wf.push_back(b.paths / b.seconds * 1e-6);
                st.push_back(d.paths / d.seconds * 1e-6);
                ratio.push_back(a.seconds / b.seconds);
                st_ratio.push_back(a.seconds / d.seconds);
                if (t > 1) {
                    mk_alone.push_back(independent_mpaths(t, each, megakernel));
                    wf_alone.push_back(independent_mpaths(t, each, wavefront));
                }
            }
            const double mk_p = spread(mk).median, wf_p = spread(wf).median;
            const double st_p = spread(st).median;
            const double q = spread(ratio).median, st_q = spread(st_ratio).median;
            if (t == 1) {
                base_mk = mk_p;
                base_wf = wf_p;
                base_st = st_p;
            }
            const double mk_up = mk_p / base_mk, wf_up = wf_p / base_wf, st_up = st_p / base_st;
            const double mk_split = speedup_of(mk_alone, &Independent::until_last, base_mk);
            const double wf_split = speedup_of(wf_alone, &Independent::until_last, base_wf);
            const double mk_busy = speedup_of(mk_alone, &Independent::own_rates, base_mk);
            const double wf_busy = speedup_of(wf_alone, &Independent::own_rates, base_wf);
            r.row("scaling", {name, "megakernel", t, cfg.spp, mk_p, mk_up, mk_up / t, q, mk_split,
                              mk_up / mk_split, mk_busy, arithmetic[c]});
            r.row("scaling", {name, "wavefront", t, cfg.spp, wf_p, wf_up, wf_up / t, q, wf_split,
                              wf_up / wf_split, wf_busy, arithmetic[c]});
            r.row("scaling", {name, "stage", t, cfg.spp, st_p, st_up, st_up / t, st_q, wf_split,
                              st_up / wf_split, wf_busy, arithmetic[c]});
            std::printf(
                "scaling %-10s %2d threads %3d spp: speed-up megakernel %5.2fx, wavefront %5.2fx, "
                "stage %5.2fx (efficiency %.2f, %.2f, %.2f); %d renders alone at once %5.2fx, "
                "%5.2fx (their own rates %5.2fx, %5.2fx); over the megakernel: wavefront %.2f, "
                "stage %.2f\n",
                name, t, cfg.spp, mk_up, wf_up, st_up, mk_up / t, wf_up / t, st_up / t, t, mk_split,
                wf_split, mk_busy, wf_busy, q, st_q);
            std::fflush(stdout);
        }
    }
}

}  // namespace wavetrace::bench
