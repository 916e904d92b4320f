// Builds a scene in code, renders it with render() and an observer, once with each engine,
// and checks what came back: a user of the installed library does no more than this.
#include <atomic>
#include <cmath>
#include <cstdio>

#include "wavetrace/wavetrace.h"

namespace {
class Count : public wavetrace::RenderObserver {
  public:
    bool on_pass(int, int, const wavetrace::Film&) override {
        ++calls;
        return true;
    }
    void on_progress(double fraction) override {
        if (fraction >= 1.0) finished = true;  // called from worker threads, concurrently
    }
    int calls = 0;
    std::atomic<bool> finished{false};
};
}  // namespace

int main() {
    using namespace wavetrace;
    Scene scene;
    Material light;
    light.kind = MaterialKind::DiffuseLight;
    light.emission = scene.add_solid(Color(4.0f));
    Material white;
    white.albedo = scene.add_solid(Color(0.7f));
    const MaterialId l = scene.add_material(light), w = scene.add_material(white);
    scene.add_quad({{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, l, kNone});  // facing down
    scene.add_box({-3, -1, -3}, {3, 0, 3}, w, kNone);               // a floor slab
    scene.camera.look_from = {0, 1, 6};
    scene.camera.look_at = {0, 0, 0};
    Bvh bvh = Bvh::build(scene);

    RenderRequest request;
    request.width = 32;
    request.height = 24;
    request.spp = 4;
    request.estimator.strategy = Strategy::Nee;
    double means[2] = {0, 0};
    int failures = 0;
    for (Engine engine : {Engine::Megakernel, Engine::Wavefront}) {
        request.engine = engine;
        Film film(request.width, request.height);
        Count count;
        const RenderStats stats = render(scene, bvh, request, film, &count);
        const Image image = film.mean();
        double sum = 0;
        for (const Color& c : image.pixels) sum += c.x + c.y + c.z;
        means[engine == Engine::Wavefront] = sum / (3.0 * image.pixels.size());
        std::printf("consumer: %s, %d spp, %d observer passes, mean %.6f\n", to_string(engine),
                    stats.spp_done, count.calls, means[engine == Engine::Wavefront]);
        if (stats.spp_done != 4 || count.calls < 2 || !count.finished || !(sum > 0)) ++failures;
    }
    std::printf("consumer: wavetrace %s (%s)\n", build_info().version.c_str(),
                build_info().simd.c_str());
    // The same paths from the same seed: the same image up to the order of additions.
    const bool same = std::fabs(means[0] - means[1]) <= 1e-5 * means[0];
    return failures == 0 && same ? 0 : 1;
}
