#include "wavetrace/engines/render.h"

#include <cinttypes>
#include <cstdio>

#include "engines/dispatch.h"
#include "wavetrace/accel/bvh.h"

namespace wavetrace {

const char* to_string(Engine e) {
    return e == Engine::Megakernel ? "megakernel" : "wavefront";
}

std::optional<Engine> parse_engine(const std::string& name) {
    for (Engine e : {Engine::Wavefront, Engine::Megakernel})
        if (name == to_string(e)) return e;
    return std::nullopt;
}

const char* to_string(Schedule s) {
    return s == Schedule::Stage ? "stage" : "resident";
}

std::optional<Schedule> parse_schedule(const std::string& name) {
    for (Schedule s : {Schedule::Resident, Schedule::Stage})
        if (name == to_string(s)) return s;
    return std::nullopt;
}

std::string film_settings(uint64_t scene_fingerprint, const RenderRequest& request) {
    const Estimator& e = request.estimator;
    char fingerprint[17];
    std::snprintf(fingerprint, sizeof fingerprint, "%016" PRIx64, scene_fingerprint);
    return "scene_fnv1a=" + std::string(fingerprint) + "\nwidth=" + std::to_string(request.width) +
           "\nheight=" + std::to_string(request.height) + "\nseed=" + std::to_string(request.seed) +
           "\nengine=" + to_string(request.engine) + "\nstrategy=" + to_string(e.strategy) +
           "\nmis_heuristic=" + (e.heuristic == MisHeuristic::Balance ? "balance" : "power") +
           "\nmax_depth=" + std::to_string(e.max_depth) + "\n" +
           // Only for a sampler other than independent: a film without the line is the
           // independent sampler's, as every film written before samplers existed is.
           (request.sampler == SamplerKind::Independent
                ? std::string()
                : "sampler=" + std::string(to_string(request.sampler)) + "\n") +
           (request.sampler == SamplerKind::ZSobol
                ? "zsobol_spp=" + std::to_string(1L << request_sampler(request).log2_spp) + "\n"
                : std::string());
}

Sampler request_sampler(const RenderRequest& request) {
    if (request.sampler != SamplerKind::ZSobol) return Sampler{request.seed, request.sampler};
    return zsobol_sampler(
        request.seed, request.width, request.height,
        request.sampler_spp > 0 ? request.sampler_spp : request.first_sample + request.spp);
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
    return render_with(scene, bvh, request, film, observer);
}

}  // namespace wavetrace
