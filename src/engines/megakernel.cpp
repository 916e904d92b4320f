#include "engines/megakernel.h"

#include "wavetrace/render/megakernel.h"
#include "wavetrace/scene/bvh.h"

namespace wavetrace {

Film render_megakernel(const Scene& scene,
                       const Bvh& bvh,
                       const RenderConfig& config,
                       RenderStats* stats,
                       const ProgressCallback& progress) {
    return megakernel(scene, bvh, config, stats, progress);
}

}  // namespace wavetrace
