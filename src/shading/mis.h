// Multiple importance sampling weights (Veach, "Robust Monte Carlo Methods for Light
// Transport Simulation", 1997, §9.2): the weight of technique a against technique b, both as
// densities of the same sample.
#pragma once

#include "wavetrace/shading/estimator.h"

namespace wavetrace {

// Balance: p_a / (p_a + p_b). Power (beta = 2): p_a^2 / (p_a^2 + p_b^2). Guarded: an infinite
// density takes all the weight; two zero densities give 0; never NaN. The one-lane instance of
// MisWeight (src/shading/mis-inl.h), which the wavefront's kernels run over SIMD lanes.
float mis_weight(MisHeuristic h, float pdf_a, float pdf_b);

// The heuristics of a render: the configured one for light at a finite distance; for light at
// infinity (an environment map's shadow rays have no end; escaping rays find it) the balance
// heuristic where the map is sampled with MIS compensation, the density derived as the best
// for that heuristic, whose combination samples the two densities' mixture (Karlík et al.,
// "MIS compensation", 2019). Directional lights are deltas: weight 1 under either.
struct MisHeuristics {
    MisHeuristic finite = MisHeuristic::Power;
    MisHeuristic at_infinity = MisHeuristic::Power;
    MisHeuristic of(bool infinite) const { return infinite ? at_infinity : finite; }
};

}  // namespace wavetrace
