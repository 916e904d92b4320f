// The wavefront's stages, one per file, each a free function over entries [begin, end) of one
// thread's wave. Per bounce:
//   intersect -> sort_by_material -> shade (light sample appended as a shadow ray)
//   -> intersect_shadow -> mis_combine -> accumulate_film (paths that ended) -> compact
// after generate has filled the wave with camera rays.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "kernels/intersect.h"         // intersect(_coherent): closest hit of rays[i] into hits[i]
#include "kernels/intersect_shadow.h"  // intersect_shadow: transmittance along shadows[i]
#include "kernels/wave.h"

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

// Entries [begin, end) start sample `sample` of the pixels visited first_index + entry-th in
// the pass: the path state and the camera ray.
void generate(const WaveInputs& in,
              uint32_t sample,
              uint32_t first_index,
              size_t begin,
              size_t end,
              PathQueue& paths,
              RayQueue& rays);

// Misses, then each MaterialKind of the hit's material.
inline constexpr int kSortKeys = 8;
// Start of each key's range after sort_by_material; entry kSortKeys is n.
using KeyRanges = std::array<uint32_t, kSortKeys + 1>;
int sort_key(const Scene& scene, PrimRef prim);

// Reorders entries [0, n) of paths, rays and hits together, in place, so that each sort key's
// entries are contiguous (an in-place counting sort, "American flag sort": McIlroy, Bostic and
// McIlroy 1993). Moves the data, not indices, so shading reads each range contiguously.
KeyRanges sort_by_material(const Scene& scene,
                           size_t n,
                           std::span<uint8_t> key,
                           PathQueue& paths,
                           RayQueue& rays,
                           HitQueue& hits);

// Entries [begin, end): resolves the segment (medium scattering, emission with its weight,
// boundary crossings); at a scattering vertex samples a light, appending the shadow ray and
// its weighted, unoccluded contribution at shadows[first_shadow + k], then samples the
// continuation with Russian roulette and writes the next ray over the entry. keep[i] = 1 if
// the path goes on. Returns the shadow rays appended.
size_t shade(const WaveInputs& in,
             uint32_t sample,
             const HitQueue& hits,
             size_t begin,
             size_t end,
             PathQueue& paths,
             RayQueue& rays,
             std::span<uint8_t> keep,
             ShadowQueue& shadows,
             size_t first_shadow);

// Adds each shadow ray's contribution, times its transmittance, to its path.
void mis_combine(const ShadowQueue& shadows,
                 std::span<const float> transmittance,
                 size_t begin,
                 size_t end,
                 PathQueue& paths);

// Adds the radiance of the paths that ended (keep[i] == 0) among entries [0, n) to the film.
void accumulate_film(const PathQueue& paths, std::span<const uint8_t> keep, size_t n, Film& film);

// Moves the entries with keep[i] != 0 among [0, n) to the front, in order; returns their count.
size_t compact(std::span<const uint8_t> keep, size_t n, PathQueue& paths, RayQueue& rays);

}  // namespace wavetrace
