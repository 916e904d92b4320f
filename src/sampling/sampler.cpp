#include "sampling/sampler.h"

#include "sampling/sampler-inl.h"

namespace wavetrace {

const char* to_string(SamplerKind s) {
    switch (s) {
        case SamplerKind::Sobol:
            return "sobol";
        case SamplerKind::ZSobol:
            return "zsobol";
        case SamplerKind::Independent:
            break;
    }
    return "independent";
}

std::optional<SamplerKind> parse_sampler(const std::string& name) {
    for (SamplerKind s : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol})
        if (name == to_string(s)) return s;
    return std::nullopt;
}

Sampler zsobol_sampler(uint64_t seed, int width, int height, int spp) {
    // At most 2^20 samples to a block (the most one render takes), so that a Morton index
    // above them stays within 64 bits.
    int log2_spp = 0;
    while (log2_spp < 20 && (int64_t(1) << log2_spp) < spp) ++log2_spp;
    return Sampler{seed, SamplerKind::ZSobol, width, height, log2_spp};
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
