#include "reference/embree_engines.h"

#include "engines/megakernel.h"
#include "engines/wavefront.h"

namespace wavetrace {

static_assert(Intersector<EmbreeMirror>);

Film render_megakernel(const Scene& scene,
                       const EmbreeMirror& embree,
                       const RenderConfig& config,
                       RenderStats* stats,
                       const ProgressCallback& progress) {
    Film film(config.width, config.height);
    megakernel(scene, embree, config, film, stats, progress);
    return film;
}

Film render_wavefront(const Scene& scene,
                      const EmbreeMirror& embree,
                      const RenderConfig& config,
                      const WavefrontConfig& wavefront_config,
                      RenderStats* stats,
                      const ProgressCallback& progress) {
    Film film(config.width, config.height);
    wavefront(scene, embree, config, film, wavefront_config, stats, progress);
    return film;
}

}  // namespace wavetrace
