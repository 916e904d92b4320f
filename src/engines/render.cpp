#include "wavetrace/engines/render.h"

#include "engines/megakernel.h"
#include "engines/wavefront.h"

namespace wavetrace {

const char* to_string(Engine e) {
    return e == Engine::Megakernel ? "megakernel" : "wavefront";
}

std::optional<Engine> parse_engine(const std::string& name) {
    for (Engine e : {Engine::Wavefront, Engine::Megakernel})
        if (name == to_string(e)) return e;
    return std::nullopt;
}

bool RenderObserver::on_pass(int, int, const Film&) {
    return true;
}

void RenderObserver::on_progress(double) {}

RenderStats render(const Scene& scene,
                   const Bvh& bvh,
                   const RenderRequest& request,
                   Film& film,
                   RenderObserver* observer) {
    if (request.engine == Engine::Megakernel)
        return render_megakernel(scene, bvh, request, film, observer);
    return render_wavefront(scene, bvh, request, film, observer);
}

}  // namespace wavetrace
