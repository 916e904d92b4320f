// The emission that a bounce's segments found (emitters hit, a background escaped to), appended
// by shade with what the strategy's weight needs; mis_combine weights and adds it.
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// Bits of an entry's flags: the previous vertex was the camera or could not sample lights (the
// emission counts fully); the emission is the background's, found by leaving the scene.
enum EmissionFlags : uint8_t { kCountsFully = 1, kAtInfinity = 2 };

#define WAVETRACE_EMISSION_FIELDS(F)                                                         \
    F(uint32_t, path, "entry of the path queue it belongs to")                               \
    F(Color, radiance, "beta Le: unweighted")                                                \
    F(float, pdf_bsdf, "density with which the previous vertex sampled the segment")         \
    F(float, pdf_light, "density with which its light sample would have (MIS only; else 0)") \
    F(uint8_t, flags, "EmissionFlags")

WAVETRACE_SOA(EmissionQueue, WAVETRACE_EMISSION_FIELDS);

}  // namespace wavetrace
