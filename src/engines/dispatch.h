// The engine a request names, on any intersector: render() on our BVH (render.cpp) and on
// Embree (src/embree) are this one call.
#pragma once

#include "accel/intersector.h"
#include "engines/megakernel.h"
#include "engines/wavefront.h"
#include "wavetrace/engines/render.h"

namespace wavetrace {

template <Intersector Tracer>
RenderStats render_with(const Scene& scene,
                        const Tracer& tracer,
                        const RenderRequest& request,
                        Film& film,
                        RenderObserver* observer) {
    if (request.engine == Engine::Megakernel)
        return megakernel(scene, tracer, request, film, observer);
    return wavefront(scene, tracer, request, film, observer);
}

}  // namespace wavetrace
