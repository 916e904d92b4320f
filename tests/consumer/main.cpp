// Builds a scene in code, renders it with the engine-agnostic render() and an observer, and
// checks what came back: a user of the installed library does no more than this.
#include <cstdio>

#include "wavetrace/wavetrace.h"

namespace {
class Count : public wavetrace::RenderObserver {
  public:
    bool on_pass(int, int, const wavetrace::Film&) override {
        ++calls;
        return true;
    }
    int calls = 0;
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
    request.config.width = 32;
    request.config.height = 24;
    request.config.spp = 4;
    request.engine = Engine::Megakernel;
    Film film(32, 24);
    Count count;
    RenderStats stats = render(scene, bvh, request, film, &count);
    const Image image = film.mean();
    double sum = 0;
    for (const Color& c : image.pixels) sum += c.x + c.y + c.z;
    std::printf("consumer: %d spp, %d observer calls, mean %.4f, wavetrace %s (%s)\n",
                stats.spp_done, count.calls, sum / (3.0 * image.pixels.size()),
                build_info().version.c_str(), build_info().simd.c_str());
    return stats.spp_done == 4 && count.calls >= 1 && sum > 0 ? 0 : 1;
}
