// What survives a bounce, per path slot of a wave (slot = index in the wave).
#pragma once

#include <cstdint>

#include "queues/soa.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/shading/medium_stack.h"
#include "wavetrace/shading/path_vertex.h"

namespace wavetrace {

#define WAVETRACE_PATH_STATE_FIELDS(F)                                                   \
    F(uint32_t, pixel, "film pixel index")                                               \
    F(uint32_t, sample, "sample index within the pixel")                                 \
    F(int32_t, bounce, "index of the vertex the current ray will reach (0: camera ray)") \
    F(Color, beta, "path throughput")                                                    \
    F(Color, radiance, "radiance gathered so far")                                       \
    F(PreviousVertex, prev, "previous vertex: position, BSDF pdf, counts-fully flag")    \
    F(MediumStack, media, "media the current ray travels in")                            \
    F(float, flight, "optical depth the current segment may still travel in media")      \
    F(uint16_t, crossings, "medium boundaries crossed by the current segment")

WAVETRACE_SOA(PathState, WAVETRACE_PATH_STATE_FIELDS);

}  // namespace wavetrace
