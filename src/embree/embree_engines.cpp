#include "embree/embree_engines.h"

#include "engines/megakernel.h"
#include "engines/wavefront.h"

namespace wavetrace {

static_assert(Intersector<EmbreeMirror>);

RenderStats render(const Scene& scene,
                   const EmbreeMirror& embree,
                   const RenderRequest& request,
                   Film& film,
                   RenderObserver* observer) {
    if (request.engine == Engine::Megakernel)
        return megakernel(scene, embree, request, film, observer);
    return wavefront(scene, embree, request, film, observer);
}

}  // namespace wavetrace
