// Both engines at equal settings on each benchmark scene, each with our BVH and with Embree as
// its intersector (the megakernel with Embree is a plain Embree path tracer: the in-house
// anchor), and the wavefront's stage schedule on our BVH; repetitions interleaved (A B C D E A B
// C D E) so that the machine's drift hits all alike.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "embree/embree_engines.h"
#include "engines/wavefront.h"
#include "sections.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

namespace {

// Peak memory of one render by the CLI in a process of its own (its summary line reports
// getrusage's peak): the per-engine figure that two engines in one process cannot give.
double cli_peak_mib(const std::string& scene, const char* engine, const RenderRequest& c) {
    const std::filesystem::path image = std::filesystem::temp_directory_path() /
                                        ("wavetrace-bench-" + std::to_string(getpid()) + ".pfm");
    std::string cmd = std::string("'") + WAVETRACE_CLI_PATH + "' render '" + scene + "' --engine " +
                      engine + " --width " + std::to_string(c.width) + " --height " +
                      std::to_string(c.height) + " --spp " + std::to_string(c.spp) + " -o '" +
                      image.string() + "' 2>&1";
    std::string out;
    if (FILE* f = popen(cmd.c_str(), "r")) {
        char buf[512];
        while (fgets(buf, sizeof buf, f)) out += buf;
        pclose(f);
    }
    std::error_code ec;
    std::filesystem::remove(image, ec);
    auto at = out.find("peak memory ");
    return at == std::string::npos ? -1.0 : std::stod(out.substr(at + 12));
}

}  // namespace

void bench_engines(const Options& o, Results& r) {
    r.table("engines", {"scene",
                        "threads",
                        "width",
                        "height",
                        "spp",
                        "megakernel_mpaths",
                        "wavefront_mpaths",
                        "megakernel_mrays",
                        "wavefront_mrays",
                        "ratio_min",
                        "ratio_median",
                        "ratio_max",
                        "rel_mse_between",
                        "wavefront_queue_mib",
                        "film_mib",
                        "megakernel_peak_mib",
                        "wavefront_peak_mib",
                        "megakernel_embree_mpaths",
                        "wavefront_embree_mpaths",
                        "megakernel_ours_over_embree",
                        "wavefront_ours_over_embree",
                        "wavefront_over_megakernel_embree",
                        "stage_mpaths",
                        "stage_over_megakernel",
                        "stage_over_resident"});
    struct Case {
        const char* scene;
        int w, h, spp;
    };
    const Case full[] = {{"cornell", 320, 320, 16},        {"everything", 320, 320, 16},
                         {"bunny", 320, 320, 16},          {"dragon", 320, 320, 16},
                         {"veach-mis", 384, 288, 16},      {"materials", 320, 160, 16},
                         {"dragon-envmap", 320, 240, 16},  {"cornell-glass", 320, 320, 16},
                         {"cornell-mirror", 320, 320, 16}, {"cornell-smoke", 320, 320, 16},
                         {"cornell-mcguire", 320, 320, 16}};
    const int reps = o.repetitions();
    const int all = tbb::this_task_arena::max_concurrency();
    std::vector<int> thread_counts = {1};
    if (all > 1) thread_counts.push_back(all);
    for (const Case& c : full)
        for (int threads : thread_counts) {
            if (!o.wants(c.scene)) continue;
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            const std::string path = (o.scenes / (std::string(c.scene) + ".json")).string();
            Scene scene = load_scene(path);
            Bvh bvh = Bvh::build(scene);
            // As in the BVH section: Embree's default build and its fast (non-robust) traversal.
            EmbreeMirror embree(scene, RTC_BUILD_QUALITY_MEDIUM, /*robust=*/false);
            RenderRequest cfg;
            cfg.width = o.quick ? 16 : c.w;
            cfg.height = o.quick ? 16 : c.h;
            cfg.spp = o.quick ? 1 : c.spp;
            cfg.seed = 1;
            cfg.sampler = o.sampler;
            cfg.estimator.max_depth = scene.render.max_depth;
            std::vector<double> ratio, mk_paths, wf_paths, mk_rays, wf_rays, mke_paths, wfe_paths,
                mk_vs_embree, wf_vs_embree, wf_vs_mke, st_paths, st_vs_mk, st_vs_wf;
            // The wavefront's stage schedule, the same kernels with each a parallel loop.
            RenderRequest staged = cfg;
            staged.wavefront.schedule = Schedule::Stage;
            Image mk_img, wf_img;
            for (int rep = 0; rep < reps; ++rep) {
                RenderStats mk, wf, mke, wfe;
                mk = render_once(scene, bvh, cfg, Engine::Megakernel, &mk_img);
                wf = render_once(scene, bvh, cfg, Engine::Wavefront, &wf_img);
                mke = render_once(scene, embree, cfg, Engine::Megakernel);
                wfe = render_once(scene, embree, cfg, Engine::Wavefront);
                const RenderStats st = render_once(scene, bvh, staged, Engine::Wavefront);
                st_paths.push_back(st.paths / st.seconds * 1e-6);
                st_vs_mk.push_back(mk.seconds / st.seconds);
                st_vs_wf.push_back(wf.seconds / st.seconds);
                mke_paths.push_back(mke.paths / mke.seconds * 1e-6);
                wfe_paths.push_back(wfe.paths / wfe.seconds * 1e-6);
                mk_vs_embree.push_back(mke.seconds / mk.seconds);  // > 1: ours is faster
                wf_vs_embree.push_back(wfe.seconds / wf.seconds);
                wf_vs_mke.push_back(mke.seconds / wf.seconds);  // > 1: beats a plain Embree tracer
                ratio.push_back(mk.seconds / wf.seconds);       // > 1: the wavefront is faster
                mk_paths.push_back(mk.paths / mk.seconds * 1e-6);
                wf_paths.push_back(wf.paths / wf.seconds * 1e-6);
                mk_rays.push_back(mk.rays / mk.seconds * 1e-6);
                wf_rays.push_back(wf.rays / wf.seconds * 1e-6);
            }
            Spread s = spread(ratio);
            const double pixels = double(cfg.width) * cfg.height;
            // Each thread carries one wave at a time.
            const double queue_mib =
                double(wavefront_bytes_per_path()) *
                double(wavefront_wave_size(size_t(pixels), size_t(threads), cfg.wavefront)) *
                threads / (1 << 20);
            const double film_mib = pixels * Film::kBytesPerPixel / (1 << 20);
            r.row("engines", {c.scene,
                              threads,
                              cfg.width,
                              cfg.height,
                              cfg.spp,
                              spread(mk_paths).median,
                              spread(wf_paths).median,
                              spread(mk_rays).median,
                              spread(wf_rays).median,
                              s.min,
                              s.median,
                              s.max,
                              relative_mse(wf_img, mk_img),
                              queue_mib,
                              film_mib,
                              cli_peak_mib(path, "megakernel", cfg),
                              cli_peak_mib(path, "wavefront", cfg),
                              spread(mke_paths).median,
                              spread(wfe_paths).median,
                              spread(mk_vs_embree).median,
                              spread(wf_vs_embree).median,
                              spread(wf_vs_mke).median,
                              spread(st_paths).median,
                              spread(st_vs_mk).median,
                              spread(st_vs_wf).median});
            std::printf(
                "engines %-10s %d thr megakernel %6.3f Mpaths/s  wavefront %6.3f Mpaths/s  "
                "wavefront/megakernel %.2f [%.2f, %.2f] | with Embree: megakernel %6.3f, wavefront "
                "%6.3f Mpaths/s; ours/Embree: megakernel %.2f, wavefront %.2f | stage %6.3f "
                "Mpaths/s, stage/megakernel %.2f, stage/resident %.2f\n",
                c.scene, threads, spread(mk_paths).median, spread(wf_paths).median, s.median, s.min,
                s.max, spread(mke_paths).median, spread(wfe_paths).median,
                spread(mk_vs_embree).median, spread(wf_vs_embree).median, spread(st_paths).median,
                spread(st_vs_mk).median, spread(st_vs_wf).median);
            std::fflush(stdout);
        }
}

// The wavefront's speed against its wave size (paths a thread carries at once), with the
// megakernel interleaved as the yardstick; all threads. The image is large enough (1024²) that
// the waves an image is cut into for balance do not cap the sizes up to 8192 on two threads;
// `effective_wave` is the size the engine used (wavefront_wave_size).
void bench_waves(const Options& o, Results& r) {
    r.table("waves", {"scene", "wave_size", "queue_kib_per_thread", "wavefront_mpaths",
                      "megakernel_mpaths", "ratio_median", "effective_wave"});
    const size_t threads = static_cast<size_t>(tbb::this_task_arena::max_concurrency());
    const std::vector<size_t> sizes =
        o.quick ? std::vector<size_t>{64, 256}
                : std::vector<size_t>{256, 1024, 2048, 4096, 8192, 16384, 65536};
    for (const char* name : {"cornell", "dragon"}) {
        Scene scene = load_scene((o.scenes / (std::string(name) + ".json")).string());
        Bvh bvh = Bvh::build(scene);
        RenderRequest cfg;
        cfg.width = o.quick ? 16 : 1024;
        cfg.height = o.quick ? 16 : 1024;
        cfg.spp = o.quick ? 1 : 2;
        cfg.seed = 1;
        cfg.sampler = o.sampler;
        cfg.estimator.max_depth = scene.render.max_depth;
        for (size_t size : sizes) {
            const size_t effective = wavefront_wave_size(size_t(cfg.width) * size_t(cfg.height),
                                                         threads, WavefrontOptions{size});
            std::vector<double> wf_paths, mk_paths, ratio;
            for (int rep = 0; rep < (o.quick ? 1 : 3); ++rep) {
                RenderStats mk, wf;
                RenderRequest sized = cfg;
                sized.wavefront.wave_size = size;
                mk = render_once(scene, bvh, sized, Engine::Megakernel);
                wf = render_once(scene, bvh, sized, Engine::Wavefront);
                wf_paths.push_back(wf.paths / wf.seconds * 1e-6);
                mk_paths.push_back(mk.paths / mk.seconds * 1e-6);
                ratio.push_back(mk.seconds / wf.seconds);
            }
            r.row("waves", {name, double(size), wavefront_bytes_per_path() * effective / 1024.0,
                            spread(wf_paths).median, spread(mk_paths).median, spread(ratio).median,
                            double(effective)});
            std::printf(
                "waves %-8s wave %6zu (effective %6zu): wavefront %6.3f Mpaths/s, "
                "wavefront/megakernel %.2f\n",
                name, size, effective, spread(wf_paths).median, spread(ratio).median);
            std::fflush(stdout);
        }
    }
}

}  // namespace wavetrace::bench
