// Counter-based random numbers: each one is a pure function of (seed, pixel, sample index,
// dimension), with no generator state, so that an image does not depend on how its pixels
// are spread over threads (see docs/architecture.md, "Random numbers", and docs/sampling.md,
// "Samplers").
#pragma once

#include <cstdint>

#include "wavetrace/sampling/sampler.h"

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

// Dimensions come in pairs (2k, 2k + 1) that the Sobol sampler draws as one two-dimensional
// point set: the pairs that sample a 2D domain (a point on a light, a direction) are aligned.
enum BounceDim : uint32_t {
    kDimMediumDistance = 0,  // free-flight distance along the ray that reaches this vertex
    kDimLightSelect = 1,     // next-event estimation: which light ...
    kDimLightU = 2,          // ... and where on it
    kDimLightV = 3,
    kDimDirectionU = 4,  // a light- or uniformly-sampled continuation direction ...
    kDimDirectionV = 5,
    kDimBsdfU = 6,  // BSDF sampling: direction ...
    kDimBsdfV = 7,
    kDimTechnique = 8,        // one-sample strategies: which technique picks the direction
    kDimDirectionSelect = 9,  // the light choice of a light-sampled continuation
    kDimBsdfLobe = 10,        // BSDF sampling: lobe choice (dielectric reflect / refract)
    kDimRoulette = 11,        // Russian roulette
    kBounceDims = 12,
};
static_assert(kCameraDims % 2 == 0 && kBounceDims % 2 == 0 && kDimLightU % 2 == 0,
              "the pairs the Sobol sampler draws together stay aligned");
static_assert(kDimDirectionU % 2 == 0 && kDimTechnique % 2 == 0 &&
                  kDimDirectionSelect == kDimTechnique + 1,
              "the one-sample strategies' dimensions fill two pairs of their own");

// Whether only the one-sample strategies (Strategy::Mixture and ::Light) read bounce dimension
// pair p, dimensions 2p and 2p + 1: their light- or uniformly-sampled direction, and their
// technique and light choice. The others' vertices leave these two pairs undrawn.
constexpr bool one_sample_pair(uint32_t p) {
    return p == kDimDirectionU / 2 || p == kDimTechnique / 2;
}

constexpr uint32_t bounce_dim(int bounce, BounceDim d) {
    return kCameraDims + static_cast<uint32_t>(bounce) * kBounceDims + d;
}

// A uniform float in [0, 1): dimension `dim` of sample `sample` of `pixel`, from the sampler
// (sampling/sampler-inl.h: the one formula both engines draw from, over lanes; the
// independent sampler when given a seed alone).
float sample_1d(const Sampler& sampler, uint32_t pixel, uint32_t sample, uint32_t dim);
float sample_1d(uint64_t seed, uint32_t pixel, uint32_t sample, uint32_t dim);

}  // namespace wavetrace
