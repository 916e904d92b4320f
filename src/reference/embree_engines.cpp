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
    return megakernel(scene, embree, config, stats, progress);
}

Film render_wavefront(const Scene& scene,
                      const EmbreeMirror& embree,
                      const RenderConfig& config,
                      const WavefrontConfig& wavefront_config,
                      RenderStats* stats,
                      const ProgressCallback& progress) {
    return wavefront(scene, embree, config, wavefront_config, stats, progress);
}

}  // namespace wavetrace
