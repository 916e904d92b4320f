#include "engines/megakernel.h"

#include "wavetrace/render/megakernel.h"
#include "wavetrace/scene/bvh.h"

namespace wavetrace {

Film render_megakernel(const Scene& scene,
                       const Bvh& bvh,
                       const RenderConfig& config,
                       RenderStats* stats,
                       const ProgressCallback& progress) {
    Film film(config.width, config.height);
    megakernel(scene, bvh, config, film, stats, progress);
    return film;
}

void render_megakernel(const Scene& scene,
                       const Bvh& bvh,
                       const RenderConfig& config,
                       Film& film,
                       RenderStats* stats,
                       const ProgressCallback& progress) {
    megakernel(scene, bvh, config, film, stats, progress);
}

}  // namespace wavetrace
