// The wavefront engine against the megakernel (same estimator, same random numbers: the same
// image up to rounding), and its determinism.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numeric>

#include "test_paths.h"
#include "wavetrace/render/megakernel.h"
#include "wavetrace/render/wavefront.h"
#include "wavetrace/scene/bvh.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

RenderConfig config(Strategy st, int w, int h, int spp, uint64_t seed = 11) {
    RenderConfig c;
    c.width = w;
    c.height = h;
    c.spp = spp;
    c.seed = seed;
    c.strategy = st;
    return c;
}

}  // namespace

// Every shipped scene, every strategy, 4 spp: per pixel within 1e-4 relative (or 1e-6
// absolute) in at least 99.9% of pixel channels, image means within 1e-5 relative.
TEST(Wavefront, EqualsTheMegakernel) {
    for (const char* name : {"cornell", "cornell-glass", "cornell-mirror", "cornell-smoke",
                             "everything", "bunny", "dragon", "veach-mis"}) {
        Scene scene = load_scene(scene_path(name));
        Bvh bvh = Bvh::build(scene);
        for (Strategy st :
             {Strategy::Bsdf, Strategy::Light, Strategy::Mixture, Strategy::Nee, Strategy::Mis}) {
            RenderConfig c = config(st, 40, 40, 4);
            WavefrontConfig wf;
            wf.wave_size = 700;  // several waves, the last one partial
            Image mk = render_megakernel(scene, bvh, c).mean();
            Image wv = render_wavefront(scene, bvh, c, wf).mean();
            size_t outside = 0, values = 0;
            double worst = 0, sum_mk = 0, sum_wv = 0;
            int worst_pixel = -1;
            for (size_t i = 0; i < mk.pixels.size(); ++i)
                for (int k = 0; k < 3; ++k) {
                    double a = mk.pixels[i][k], b = wv.pixels[i][k];
                    sum_mk += a;
                    sum_wv += b;
                    ++values;
                    double diff = std::fabs(a - b);
                    if (diff > 1e-6 && diff > 1e-4 * std::fabs(a)) ++outside;
                    double rel = diff / std::max(std::fabs(a), 1e-6);
                    if (rel > worst) {
                        worst = rel;
                        worst_pixel = static_cast<int>(i);
                    }
                }
            double mean_rel = std::fabs(sum_mk - sum_wv) / std::max(sum_mk, 1e-30);
            std::printf(
                "wavefront-vs-megakernel %-14s %-8s outside bound %zu/%zu, worst relative %.2e "
                "(pixel %d), image means %.2e relative\n",
                name, to_string(st), outside, values, worst, worst_pixel, mean_rel);
            EXPECT_LE(outside, values / 1000) << name << " " << to_string(st);
            EXPECT_LE(mean_rel, 1e-5) << name << " " << to_string(st);
        }
    }
}

TEST(Wavefront, BitIdenticalForAnyThreadCountAndWaveSize) {
    Scene scene = load_scene(scene_path("cornell-smoke"));
    Bvh bvh = Bvh::build(scene);
    RenderConfig c = config(Strategy::Mis, 37, 23, 5);  // 851 pixels
    auto render = [&](int threads, size_t wave, bool sort) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        WavefrontConfig wf;
        wf.wave_size = wave;
        wf.sort_by_material = sort;
        return render_wavefront(scene, bvh, c, wf).mean();
    };
    Image ref = render(1, 851, false);
    struct Run {
        int threads;
        size_t wave;
        bool sort;
    };
    for (Run r : {Run{2, 851, false}, Run{7, 851, false}, Run{2, 256, false},
                  Run{7, 300, false},  // 300 divides nothing
                  Run{1, 64, false}, Run{1, 851, true}, Run{7, 300, true}}) {
        Image img = render(r.threads, r.wave, r.sort);
        for (size_t i = 0; i < ref.pixels.size(); ++i)
            ASSERT_EQ(ref.pixels[i], img.pixels[i]) << "threads " << r.threads << " wave " << r.wave
                                                    << " sort " << r.sort << " pixel " << i;
    }
}
