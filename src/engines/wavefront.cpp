#include "engines/wavefront.h"

#include "wavetrace/render/wavefront.h"
#include "wavetrace/scene/bvh.h"

namespace wavetrace {

size_t wavefront_bytes_per_path() {
    return WaveQueues::bytes_per_path();
}

Film render_wavefront(const Scene& scene,
                      const Bvh& bvh,
                      const RenderConfig& config,
                      const WavefrontConfig& wavefront_config,
                      RenderStats* stats,
                      const ProgressCallback& progress) {
    Film film(config.width, config.height);
    wavefront(scene, bvh, config, film, wavefront_config, stats, progress);
    return film;
}

void render_wavefront(const Scene& scene,
                      const Bvh& bvh,
                      const RenderConfig& config,
                      Film& film,
                      const WavefrontConfig& wavefront_config,
                      RenderStats* stats,
                      const ProgressCallback& progress) {
    wavefront(scene, bvh, config, film, wavefront_config, stats, progress);
}

}  // namespace wavetrace
