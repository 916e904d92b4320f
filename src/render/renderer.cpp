#include "wavetrace/render/renderer.h"

#include "wavetrace/render/megakernel.h"

namespace wavetrace {

RenderStats render(const Scene& scene,
                   const Bvh& bvh,
                   const RenderRequest& request,
                   Film& film,
                   RenderObserver* observer) {
    RenderConfig config = request.config;
    const auto& user_stop = request.config.stop;
    config.stop = [&](int done) {
        if (observer && !observer->on_pass(done, request.config.spp, film)) return true;
        return user_stop && user_stop(done);
    };
    RenderStats stats;
    if (request.engine == Engine::Megakernel)
        render_megakernel(scene, bvh, config, film, &stats);
    else
        render_wavefront(scene, bvh, config, film, request.wavefront, &stats);
    // The last pass is reported too: the callbacks see the finished film.
    if (observer && stats.spp_done == request.config.spp)
        observer->on_pass(stats.spp_done, request.config.spp, film);
    return stats;
}

}  // namespace wavetrace
