#include "sampling/sampler.h"

#include "sampling/sampler-inl.h"

namespace wavetrace {

const char* to_string(SamplerKind s) {
    return s == SamplerKind::Sobol ? "sobol" : "independent";
}

std::optional<SamplerKind> parse_sampler(const std::string& name) {
    for (SamplerKind s : {SamplerKind::Independent, SamplerKind::Sobol})
        if (name == to_string(s)) return s;
    return std::nullopt;
}

float sample_1d(const Sampler& sampler, uint32_t pixel, uint32_t sample, uint32_t dim) {
    namespace lanes = HWY_NAMESPACE;
    using L = lanes::OneLane;
    return lanes::SampleDim<L>(lanes::PathState<L>(sampler, pixel, sample), dim);
}

float sample_1d(uint64_t seed, uint32_t pixel, uint32_t sample, uint32_t dim) {
    return sample_1d(Sampler{seed, SamplerKind::Independent}, pixel, sample, dim);
}

}  // namespace wavetrace
