#include "shading/mis.h"

#include "shading/mis-inl.h"

namespace wavetrace {

float mis_weight(MisHeuristic h, float pdf_a, float pdf_b) {
    namespace lanes = HWY_NAMESPACE;
    return lanes::MisWeight<lanes::OneLane>(h, pdf_a, pdf_b);
}

}  // namespace wavetrace
