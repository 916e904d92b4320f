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
    ZSobol,       // one Owen-scrambled Sobol sequence over all pixels in a shuffled Morton order
};

const char* to_string(SamplerKind s);
std::optional<SamplerKind> parse_sampler(const std::string& name);

struct Sampler {
    uint64_t seed = 0;
    SamplerKind kind = SamplerKind::Independent;
    // ZSobol's layout (the others ignore it): the image's size, for the pixels' Morton order,
    // and log2 of the samples per pixel each pixel's block of the sequence holds; samples
    // beyond a block go on in further blocks of their own scrambling.
    int width = 0, height = 0;
    int log2_spp = 0;
};

// The zsobol sampler's layout for an image and a sample count per pixel (rounded up to a
// power of two, as its blocks are; at most 2^20).
Sampler zsobol_sampler(uint64_t seed, int width, int height, int spp);

}  // namespace wavetrace
