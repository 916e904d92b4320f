// The wavefront's kernels, one per file, each a free function over entries [begin, end) of a
// wave's queues: its inputs const, its outputs mutable. After generate has filled the wave with
// camera rays, per bounce:
//   intersect -> [sort_by_material] -> shade -> light_sample -> intersect_shadow
//   -> mis_combine -> accumulate_film (the paths that ended) -> compact
// and once the wave's last path has ended, add_to_film.
// A kernel that appends to a queue writes at most one entry per entry it reads, from a first
// entry its caller gives, and returns how many it wrote: the resident schedule appends each
// bounce's entries from 0, the stage schedule each chunk's from the chunk's own first entry
// (engines/wavefront.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "kernels/intersect.h"         // intersect(_coherent): closest hit of rays[i] into hits[i]
#include "kernels/intersect_shadow.h"  // intersect_shadow: transmittance along shadows[i]
#include "kernels/wave.h"
#include "shading/mis.h"

namespace wavetrace {

// The pixel visited k-th in a pass: the image in bands of 2 rows, each band in 4x2 tiles, so
// that a wave's consecutive camera rays form the pixel tiles packets trace well. A bijection
// of [0, width * height).
uint32_t pixel_in_pass_order(uint32_t k, uint32_t width, uint32_t height);
// The same pixels for k, k + 1, ... in turn, stepping through the tiles instead of dividing
// for each one (pixel_in_pass_order's five divisions were most of what generate cost).
class PassOrderWalk {
  public:
    PassOrderWalk(uint32_t k, uint32_t width, uint32_t height);
    uint32_t x() const { return kTileW * tile_ + dx_; }
    uint32_t y() const { return kTileH * band_ + dy_; }
    void next();

  private:
    static constexpr uint32_t kTileW = 4, kTileH = 2;
    uint32_t width_, height_;
    uint32_t band_, tile_;      // the current tile: its band of rows, its place in the band
    uint32_t tile_w_, band_h_;  // its size (smaller at the right and bottom edges)
    uint32_t dx_, dy_;          // the pixel within it
};

// Entries [begin, end) of a wave of the pixels visited first_index-th, first_index + 1-th, ...
// in the pass, each carrying the samples `samples` side by side: entry i starts sample
// samples.first + i % samples.per_pixel of the pixel visited (first_index + i /
// samples.per_pixel)-th, its path state and camera ray. Its radiance goes to slot i of the
// wave's film.
void generate(const WaveInputs& in,
              WaveSamples samples,
              uint32_t first_index,
              size_t begin,
              size_t end,
              PathQueue& paths,
              RayQueue& rays);

// Misses, then each MaterialKind of the hit's material.
inline constexpr int kSortKeys = 1 + kMaterialKinds;
// Start of each key's range after sort_by_material; entry kSortKeys is the range's end.
using KeyRanges = std::array<uint32_t, kSortKeys + 1>;
int sort_key(const Scene& scene, PrimRef prim);

// Reorders entries [begin, end) of paths, rays and hits together, in place, so that each sort
// key's entries are contiguous (an in-place counting sort, "American flag sort": McIlroy, Bostic
// and McIlroy 1993). Moves the data, not indices, so shading reads each range contiguously.
KeyRanges sort_by_material(const Scene& scene,
                           size_t begin,
                           size_t end,
                           std::span<uint8_t> key,
                           PathQueue& paths,
                           RayQueue& rays,
                           HitQueue& hits);

// Entries [begin, end): resolves each path's segment (medium scattering, emission found,
// boundary crossings, the vertex it scatters at), appending the emission found, unweighted with
// the densities its weight needs, to `emissions` from entry first_emission, and each scattering
// vertex that samples a light to `light_samples` from entry first_light_sample; then samples
// the continuation with Russian roulette and writes the next ray over the entry. keep[i] = 1 if
// the path goes on.
struct ShadeCounts {
    size_t light_samples = 0, emissions = 0;  // entries appended
};
ShadeCounts shade(const WaveInputs& in,
                  const HitQueue& hits,
                  size_t begin,
                  size_t end,
                  PathQueue& paths,
                  RayQueue& rays,
                  std::span<uint8_t> keep,
                  LightSampleQueue& light_samples,
                  size_t first_light_sample,
                  EmissionQueue& emissions,
                  size_t first_emission);

// Entries [begin, end) of the light-sample queue: picks each vertex's light and a point on it,
// evaluates the BSDF towards it and appends the shadow ray with its unweighted contribution
// and both densities at shadows[first_shadow + k]; where the vertex is its path's previous
// vertex (not a thin sheet passed), the choice's importance sum in the path's prev_total.
// Returns the shadow rays appended.
size_t light_sample(const WaveInputs& in,
                    const LightSampleQueue& queue,
                    size_t begin,
                    size_t end,
                    ShadowQueue& shadows,
                    size_t first_shadow,
                    PathQueue& paths);

// Weights and adds to their paths the emission found (entries `found` of emissions) and each
// shadow ray's contribution times its transmittance (entries `shadowed`): the MIS weights of
// the strategy (shading/path_vertex.h's emission_weight and direct_weight, by `heuristics`:
// mis_heuristics'), computed only here.
void mis_combine(const Estimator& estimator,
                 MisHeuristics heuristics,
                 const EmissionQueue& emissions,
                 EntryRange found,
                 const ShadowQueue& shadows,
                 std::span<const Color> transmittance,
                 EntryRange shadowed,
                 PathQueue& paths);

// Stores the radiance of the paths that ended (keep[i] == 0) among entries [begin, end) in their
// slots of the wave's film.
void accumulate_film(const PathQueue& paths,
                     std::span<const uint8_t> keep,
                     size_t begin,
                     size_t end,
                     WaveFilm& film);
// Once every path of the wave has ended: adds the wave's film to the image for the pixels
// [begin, end) of the wave (generate's order), each pixel's samples in sample order.
void add_to_film(const WaveInputs& in,
                 uint32_t first_index,
                 WaveSamples samples,
                 size_t begin,
                 size_t end,
                 const WaveFilm& wave_film,
                 Film& film);

// Moves the entries with keep[i] != 0 among [0, n) to the front, in order; returns their count.
size_t compact(std::span<const uint8_t> keep, size_t n, PathQueue& paths, RayQueue& rays);
// The same from one pair of queues to another: the kept entries among [begin, end) of `paths`
// and `rays` to next_paths and next_rays from entry `to`, in order; returns their count.
size_t compact_into(std::span<const uint8_t> keep,
                    size_t begin,
                    size_t end,
                    const PathQueue& paths,
                    const RayQueue& rays,
                    size_t to,
                    PathQueue& next_paths,
                    RayQueue& next_rays);

}  // namespace wavetrace
