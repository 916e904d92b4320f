#include "engines/wavefront.h"

#include <algorithm>

#include "wavetrace/accel/bvh.h"

namespace wavetrace {

// Guided self-scheduling of a pass's waves. A wave carries its pixels through all the
// samples of a pass, so its last waves decide when the threads meet again; equal waves must
// be small for balance (64 per thread made the dragon 4.5% faster than 16 at 2 threads), and
// small waves cost per wave and per chunk (100 paths: cornell -10%, 256: -3% against 1,600 at
// one thread). Shrinking waves give both: large ones while many pixels are left, a share of
// 1 / (kGuidedShare threads) of what is left each, and small ones only at the end.
constexpr size_t kGuidedShare = 2;
constexpr size_t kMinWave = 128;
// A wave covers at most 1/kImageShare of the image (and kMinImageWave pixels where that is
// fewer): its paths' hits then lie in a small part of the scene, whose nodes and textures stay
// in cache from path to path. A small image's wave carries several samples of each of its
// pixels instead (wave_samples_per_pixel), as the megakernel keeps a tile's samples together.
// (The share is measured in docs/benchmarks.md, "Small images".)
constexpr size_t kImageShare = 64;
constexpr size_t kMinImageWave = 32;

namespace {

// The size of the wave taken when `left` of `pixels` pixels are left.
size_t guided_wave(size_t left, size_t pixels, size_t threads, const WavefrontOptions& wavefront) {
    const size_t most = wavefront_wave_pixels(pixels, wavefront);
    const size_t parts = kGuidedShare * std::max<size_t>(threads, 1);
    return std::min(left, std::clamp((left + parts - 1) / parts, std::min(kMinWave, most), most));
}

}  // namespace

size_t wavefront_wave_pixels(size_t pixels, const WavefrontOptions& wavefront) {
    const size_t share = std::max(pixels / kImageShare, kMinImageWave);
    return std::max<size_t>(1, std::min({wavefront.wave_size, pixels, share}));
}

std::vector<WaveRange> wavefront_waves(size_t pixels,
                                       size_t threads,
                                       const WavefrontOptions& wavefront) {
    std::vector<WaveRange> waves;
    for (size_t first = 0; first < pixels;) {
        const size_t n = guided_wave(pixels - first, pixels, threads, wavefront);
        waves.push_back({first, n});
        first += n;
    }
    return waves;
}

// The first wave is the largest: the share of what is left only shrinks.
size_t wavefront_wave_size(size_t pixels, size_t threads, const WavefrontOptions& wavefront) {
    return pixels == 0 ? 1 : guided_wave(pixels, pixels, threads, wavefront);
}

size_t wavefront_wave_paths(size_t wave_pixels, size_t pixels, int spp, size_t paths_per_wave) {
    const size_t most = std::min(paths_per_wave, pixels * size_t(std::max(spp, 1)));
    return std::max(wave_pixels, most);
}

size_t wavefront_bytes_per_path() {
    return WaveQueues::bytes_per_path();
}

}  // namespace wavetrace
