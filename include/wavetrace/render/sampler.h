// Counter-based random numbers: each one is a pure function of (seed, pixel, sample index,
// dimension), with no generator state, so that an image does not depend on how its pixels
// are spread over threads (see docs/architecture.md, "Random numbers").
#pragma once

#include <cstdint>

namespace wavetrace {

// The dimension layout: the camera's dimensions first, then kBounceDims per path vertex
// (bounce b uses kCameraDims + b * kBounceDims + BounceDim). Both engines draw every decision
// from here, so the same (seed, pixel, sample) traces the same path in either.
enum SampleDim : uint32_t {
    kDimPixelX = 0,  // jitter inside the pixel
    kDimPixelY = 1,
    kDimLensU = 2,  // point on the thin lens
    kDimLensV = 3,
    kCameraDims = 4,
};

enum BounceDim : uint32_t {
    kDimMediumDistance = 0,  // free-flight distance along the ray that reaches this vertex
    kDimLightSelect = 1,     // next-event estimation: which light ...
    kDimLightU = 2,          // ... and where on it
    kDimLightV = 3,
    kDimTechnique = 4,   // one-sample strategies: which technique picks the direction
    kDimDirectionU = 5,  // a light- or uniformly-sampled continuation direction
    kDimDirectionV = 6,
    kDimDirectionSelect = 7,  // ... its light choice
    kDimBsdfLobe = 8,         // BSDF sampling: lobe choice (dielectric reflect / refract) ...
    kDimBsdfU = 9,            // ... and direction
    kDimBsdfV = 10,
    kDimRoulette = 11,  // Russian roulette
    kBounceDims = 12,
};

constexpr uint32_t bounce_dim(int bounce, BounceDim d) {
    return kCameraDims + static_cast<uint32_t>(bounce) * kBounceDims + d;
}

// SplitMix64's finaliser (Steele et al., "Fast Splittable Pseudorandom Number Generators",
// OOPSLA 2014): a bijective 64-bit mix with full avalanche.
constexpr uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// A uniform float in [0, 1) for the given coordinates: the counters are folded in one at a
// time through the mixer so that neighbouring counters give independent-looking values.
constexpr float sample_1d(uint64_t seed, uint32_t pixel, uint32_t sample, uint32_t dim) {
    uint64_t h = mix64(seed ^ 0x9e3779b97f4a7c15ULL);
    h = mix64(h ^ (static_cast<uint64_t>(pixel) << 32 | sample));
    h = mix64(h + dim);
    return static_cast<float>(h >> 40) * 0x1p-24f;  // 24 random bits: exactly representable
}

}  // namespace wavetrace
