// Which estimator of the rendering equation a render uses, and its path-length rules: what
// both engines' per-vertex code reads (see docs/sampling.md for what each strategy counts).
#pragma once

#include <optional>
#include <string>

namespace wavetrace {

// The five estimators of the rendering equation.
enum class Strategy {
    Bsdf,     // follow BSDF samples; count emission wherever a path hits a light
    Light,    // continue along light-sampled directions, with a defensive uniform component
    Mixture,  // one-sample mixture: half BSDF, half light sampling, density 0.5 p_b + 0.5 p_l
    Nee,      // next-event estimation: shadow ray per vertex; BSDF-hit emission only after delta
    Mis,      // NEE and BSDF-hit emission both, weighted by the balance or power heuristic
};

// Multiple importance sampling weights (Veach's thesis, 1997, §9.2): balance p_a / (p_a + p_b),
// power (beta = 2) p_a^2 / (p_a^2 + p_b^2).
enum class MisHeuristic { Balance, Power };

struct Estimator {
    Strategy strategy = Strategy::Mis;
    // For lights at a finite distance; a compensated environment map's is always the balance
    // heuristic (src/shading/mis.h).
    MisHeuristic heuristic = MisHeuristic::Power;
    int max_depth = 50;  // the most ray segments a path may have
    int rr_depth = 3;    // Russian roulette from this many scattering vertices on
};

const char* to_string(Strategy s);
std::optional<Strategy> parse_strategy(const std::string& name);

}  // namespace wavetrace
