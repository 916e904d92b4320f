// All of one vertex's sample dimensions at once, for the megakernel, which draws them path by
// path: the vertex's dimension pairs side by side in SIMD lanes (runtime dispatch), each lane
// computing what sampling/sampler-inl.h's one-lane instance gives for its pair, bit for bit.
// (The wavefront draws the same numbers a row of paths at a time, draw_vertex_samples.)
#pragma once

#include <cstdint>

#include "sampling/sampler.h"

namespace wavetrace {

// u[d] = dimension bounce_dim(bounce, d) of path (pixel, sample), for d < kBounceDims; without
// one_sample, 0 in the pairs only the one-sample strategies read (one_sample_pair). With
// next_flight, also the optical depth of the segment that leaves the vertex (segment_flight of
// bounce + 1), drawn in the same vectors as the vertex's pairs, as the wavefront does.
void draw_bounce_dims(const Sampler& sampler,
                      uint32_t pixel,
                      uint32_t sample,
                      int bounce,
                      bool one_sample,
                      float u[kBounceDims],
                      float* next_flight = nullptr);

}  // namespace wavetrace
