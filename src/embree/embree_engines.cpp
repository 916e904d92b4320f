#include "embree/embree_engines.h"

#include "engines/dispatch.h"

namespace wavetrace {

static_assert(Intersector<EmbreeMirror>);

RenderStats render(const Scene& scene,
                   const EmbreeMirror& embree,
                   const RenderRequest& request,
                   Film& film,
                   RenderObserver* observer) {
    return render_with(scene, embree, request, film, observer);
}

}  // namespace wavetrace
