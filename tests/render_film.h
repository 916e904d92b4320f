// The tests' shorthand for render() (wavetrace/engines/render.h): one engine's render of a
// request into a new film of its size, on our BVH or, with embree/embree_engines.h included,
// on Embree.
#pragma once

#include "wavetrace/engines/render.h"
#include "wavetrace/film/film.h"

template <class Tracer>
wavetrace::Film film_of(const wavetrace::Scene& scene,
                        const Tracer& tracer,
                        const wavetrace::RenderRequest& request,
                        wavetrace::RenderStats* stats) {
    wavetrace::Film film(request.width, request.height);
    const wavetrace::RenderStats s = render(scene, tracer, request, film);
    if (stats) *stats = s;
    return film;
}

template <class Tracer>
wavetrace::Film megakernel_film(const wavetrace::Scene& scene,
                                const Tracer& tracer,
                                wavetrace::RenderRequest request,
                                wavetrace::RenderStats* stats = nullptr) {
    request.engine = wavetrace::Engine::Megakernel;
    return film_of(scene, tracer, request, stats);
}

template <class Tracer>
wavetrace::Film wavefront_film(const wavetrace::Scene& scene,
                               const Tracer& tracer,
                               wavetrace::RenderRequest request,
                               const wavetrace::WavefrontOptions& options = {},
                               wavetrace::RenderStats* stats = nullptr) {
    request.engine = wavetrace::Engine::Wavefront;
    request.wavefront = options;
    return film_of(scene, tracer, request, stats);
}
