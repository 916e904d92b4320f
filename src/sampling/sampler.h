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

// A uniform float in [0, 1) for the given coordinates, from a hash of them (SplitMix64's
// finaliser applied to the counters folded in one at a time; 24 random bits, so every value is
// exactly representable). The one formula both engines draw from: src/sampling/sampler-inl.h,
// over lanes.
float sample_1d(uint64_t seed, uint32_t pixel, uint32_t sample, uint32_t dim);

}  // namespace wavetrace
