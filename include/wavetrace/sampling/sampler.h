// Which sequence a render's random numbers come from. Every sampler is a pure function of
// (seed, pixel, sample index, dimension), so that both engines trace the same paths and an
// image does not depend on threads, wave size, schedule, passes or how its sample ranges were
// split (docs/sampling.md, "Samplers").
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace wavetrace {

enum class SamplerKind {
    Independent,  // every number an independent uniform hash of its coordinates
    Sobol,        // per pixel, Owen-scrambled Sobol points, padded in shuffled pairs of dimensions
};

const char* to_string(SamplerKind s);
std::optional<SamplerKind> parse_sampler(const std::string& name);

struct Sampler {
    uint64_t seed = 0;
    SamplerKind kind = SamplerKind::Independent;
};

}  // namespace wavetrace
