// Captured ray batches and the interleaved timing of tracers over them: what the BVH and the
// scene-size sections measure ours and Embree with.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "wavetrace/accel/bvh.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
class EmbreeMirror;
}

namespace wavetrace::bench {

struct Batches {
    std::vector<Ray> primary, diffuse, shadow;
};

// Primary rays of a side x side image in 4 x 2 pixel tiles (so that 8 consecutive rays form a
// coherent packet and 16 form two), then from each primary hit a cosine-distributed bounce
// and, where the scene has lights, a shadow ray to a light sample.
Batches capture(const Scene& scene, const Bvh& bvh, int side);

// How a batch is traced: `step` rays per call of `trace(first ray)`.
struct Tracer {
    size_t step;
    std::function<void(size_t)> trace;
};

// Passes of every tracer over the same rays, interleaved (A B C A B C ...) so that a shared
// machine's drift falls on all of them alike: runs[k][j] is tracer j's Mrays/s in round k;
// `threads` 1 runs serially.
std::vector<std::vector<double>> interleaved(const std::vector<Ray>& rays,
                                             int threads,
                                             const std::vector<Tracer>& tracers,
                                             int rounds);

// Tracer j's median rate, and the median over rounds of tracer a's rate over tracer b's.
double median_rate(const std::vector<std::vector<double>>& runs, size_t j);
double median_ratio(const std::vector<std::vector<double>>& runs, size_t a, size_t b);

// Our BVH's and Embree's single rays over `rays` (closest hits; occlusion for shadow rays),
// and with `packets` our 8-ray packets and Embree's 8- and 16-wide ones, timed in `rounds`
// interleaved rounds: medians, the ratios as medians of the rounds' ratios.
struct BatchRates {
    double ours = 0, embree = 0, ours_over_embree = 0;  // single rays, Mrays/s
    bool packets = false;
    double ours_packet = 0, embree_packet8 = 0, embree_packet16 = 0, ours_packet_over_embree16 = 0;
};
BatchRates time_batch(const Bvh& bvh,
                      const EmbreeMirror& embree,
                      const std::vector<Ray>& rays,
                      bool shadow,
                      bool packets,
                      int threads,
                      int rounds);

// time_batch over b's primary (with packets), diffuse and shadow batches in that order, each
// reported as report(batch name, its ray count, its rates).
void time_batches(const Bvh& bvh,
                  const EmbreeMirror& embree,
                  const Batches& b,
                  int threads,
                  int rounds,
                  const std::function<void(const char*, size_t, const BatchRates&)>& report);

// The median of `times` calls of `build` (each returning its milliseconds).
double median_ms(const std::function<double()>& build, int times = 3);

}  // namespace wavetrace::bench
