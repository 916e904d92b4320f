// Multiple importance sampling weights (Veach, "Robust Monte Carlo Methods for Light
// Transport Simulation", 1997, §9.2): the weight of technique a against technique b, both as
// densities of the same sample.
#pragma once

#include <cmath>

namespace wavetrace {

enum class MisHeuristic { Balance, Power };

// Balance: p_a / (p_a + p_b). Power (beta = 2): p_a^2 / (p_a^2 + p_b^2). Guarded: an infinite
// density takes all the weight; two zero densities give 0; never NaN.
inline float mis_weight(MisHeuristic h, float pdf_a, float pdf_b) {
    if (std::isinf(pdf_a)) return 1.0f;
    if (std::isinf(pdf_b) || !(pdf_a > 0.0f)) return 0.0f;
    if (!(pdf_b > 0.0f)) return 1.0f;
    if (h == MisHeuristic::Balance) return pdf_a / (pdf_a + pdf_b);
    // Divide through by the larger density so the squares cannot overflow.
    float r = pdf_b / pdf_a;
    return 1.0f / (1.0f + r * r);
}

}  // namespace wavetrace
