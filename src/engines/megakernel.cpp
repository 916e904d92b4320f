#include "engines/megakernel.h"

#include "wavetrace/accel/bvh.h"

namespace wavetrace {

RenderStats render_megakernel(const Scene& scene,
                              const Bvh& bvh,
                              const RenderRequest& request,
                              Film& film,
                              RenderObserver* observer) {
    return megakernel(scene, bvh, request, film, observer);
}

}  // namespace wavetrace
