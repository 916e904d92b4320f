// Our BVH against Embree on the same captured ray batches: coherent primary rays, incoherent
// diffuse bounces, and shadow rays; single rays on one thread and on all threads, Embree's
// 8- and 16-wide packets on the primary batch; and build times. Each row times its tracers in
// interleaved rounds and reports medians, the ratios as medians of the rounds' ratios.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <cstdio>

#include "embree/embree_mirror.h"
#include "ray_batches.h"
#include "sections.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::bench {

void bench_bvh(const Options& o, Results& r) {
    r.table("bvh", {"scene", "batch", "threads", "rays", "ours_mrays", "embree_mrays",
                    "ours_over_embree", "embree_packet8_mrays", "embree_packet16_mrays",
                    "ours_packet_mrays", "ours_packet_over_embree_packet16"});
    r.table("bvh_build", {"scene", "primitives", "ours_ms", "embree_medium_ms", "embree_high_ms"});
    const int all_threads = tbb::this_task_arena::max_concurrency();
    for (const char* name : {"cornell", "everything", "dragon", "cornell-mcguire"}) {
        Scene scene = load_scene(o.scenes / (std::string(name) + ".json"));
        Bvh bvh = Bvh::build(scene);
        EmbreeMirror embree(scene, RTC_BUILD_QUALITY_MEDIUM, /*robust=*/false);
        Batches b = capture(scene, bvh, o.quick ? 32 : 512);
        for (int threads : {1, all_threads}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            time_batches(bvh, embree, b, threads, o.repetitions(),
                         [&](const char* batch, size_t rays, const BatchRates& t) {
                             nlohmann::json p8 = nullptr, p16 = nullptr, ours_p = nullptr,
                                            ratio_p = nullptr;
                             if (t.packets) {
                                 ours_p = t.ours_packet;
                                 p8 = t.embree_packet8;
                                 p16 = t.embree_packet16;
                                 ratio_p = t.ours_packet_over_embree16;
                                 std::printf(
                                     "bvh %-10s packets  %d thread(s): ours %7.2f Mrays/s, embree "
                                     "16-wide %7.2f, ours/embree %.2f\n",
                                     name, threads, t.ours_packet, t.embree_packet16,
                                     t.ours_packet_over_embree16);
                             }
                             r.row("bvh", {name, batch, threads, rays, t.ours, t.embree,
                                           t.ours_over_embree, p8, p16, ours_p, ratio_p});
                             std::printf(
                                 "bvh %-10s %-8s %d thread(s): ours %7.2f Mrays/s, embree %7.2f, "
                                 "ours/embree %.2f\n",
                                 name, batch, threads, t.ours, t.embree, t.ours_over_embree);
                             std::fflush(stdout);
                         });
        }
        double ours = median_ms([&] { return Bvh::build(scene).stats().build_ms; });
        double medium = median_ms(
            [&] { return EmbreeMirror(scene, RTC_BUILD_QUALITY_MEDIUM, false).build_ms(); });
        double high = median_ms(
            [&] { return EmbreeMirror(scene, RTC_BUILD_QUALITY_HIGH, false).build_ms(); });
        r.row("bvh_build", {name, scene.primitive_count(), ours, medium, high});
    }
}

}  // namespace wavetrace::bench
