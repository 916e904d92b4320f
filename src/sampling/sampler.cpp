#include "sampling/sampler.h"

#include "sampling/sampler-inl.h"

namespace wavetrace {

float sample_1d(uint64_t seed, uint32_t pixel, uint32_t sample, uint32_t dim) {
    namespace lanes = HWY_NAMESPACE;
    using L = lanes::OneLane;
    return lanes::SampleDim<L>(lanes::PathState<L>(seed, pixel, sample), dim);
}

}  // namespace wavetrace
