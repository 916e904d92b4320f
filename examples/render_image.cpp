// The README's rendering example: load a scene file, render it with render(), watching the
// passes, and write the image.
#include <cstdio>

#include "wavetrace/wavetrace.h"

using namespace wavetrace;

// Called between passes on this thread (the film may be read then) and with the progress
// from the worker threads.
class Watch : public RenderObserver {
  public:
    bool on_pass(int done, int requested, const Film&) override {
        std::printf("%d of %d samples per pixel\n", done, requested);
        return true;  // false stops the render here
    }
};

int main(int argc, char** argv) {
    if (argc != 3) return 2;  // usage: render_image SCENE.json OUT.png
    try {
        const Scene scene = load_scene(argv[1]);
        const Bvh bvh = Bvh::build(scene);
        RenderRequest request;
        request.width = 160;
        request.height = 160;
        request.spp = 16;
        request.estimator.strategy = Strategy::Mis;
        request.engine = Engine::Wavefront;
        Film film(request.width, request.height);
        Watch watch;
        const RenderStats stats = render(scene, bvh, request, film, &watch);
        write_image(argv[2], film.mean());
        std::printf("%.2f Mpaths/s\n", stats.paths / stats.seconds * 1e-6);
        return stats.spp_done == request.spp ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
}
