// The wavefront's stages, one per file, each a free function over [begin, end).
//   generate -> intersect -> bucket_by_material -> shade -> light_sample -> (compact shadow)
//   -> intersect_shadow -> mis_combine -> (compact rays) -> ... -> accumulate_film
#pragma once

#include <cstddef>
#include <cstdint>

#include "kernels/intersect.h"         // intersect: closest hit of rays[i] into hits[i]
#include "kernels/intersect_shadow.h"  // intersect_shadow: transmittance along shadow[i]
#include "kernels/wave.h"

namespace wavetrace {

// Path slots [begin, end) start sample number first_global + slot of the render (pixel =
// global % pixels, sample = global / pixels): camera ray into rays[slot].
void generate(const WaveInputs& in, WaveQueues& q, uint64_t first_global, size_t begin, size_t end);

// Fills q.order[0, n) with the ray entries grouped by the material kind of their hit
// (misses first), stably. Not range-split: a counting sort over the whole queue.
void bucket_by_material(const WaveInputs& in, WaveQueues& q, size_t n);

// For q.order[k], k in [begin, end): resolve the segment (medium scattering, emission with its
// weight, boundary crossings), store the vertex for light sampling, sample the continuation
// with Russian roulette, update the path and write its next ray over the entry.
void shade(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end);

// For ray entries with a stored vertex: a light sample, as an unweighted shadow-ray candidate.
void light_sample(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end);

// Adds each shadow ray's contribution, times its MIS weight and transmittance, to its path.
void mis_combine(const WaveInputs& in, WaveQueues& q, size_t begin, size_t end);

// Adds the wave's finished paths to the film, in slot order.
void accumulate_film(const WaveQueues& q, Film& film, size_t slots);

}  // namespace wavetrace
