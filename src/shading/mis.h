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

}  // namespace wavetrace
