// Arbitrary output variables from primary rays: what the camera sees first, without light
// transport. They need no engine and stay useful beside one (denoiser features, debugging).
#pragma once

#include <cstdint>
#include <string_view>

#include "wavetrace/image/image.h"

namespace wavetrace {

struct Scene;
class Bvh;

enum class Aov {
    Albedo,  // the first surface's reflectance (emitters: radiance scaled to max 1; misses: 0)
    Normal,  // its unit shading normal, facing the camera, in world space; misses: 0
    Depth,   // distance from the camera to it; misses: +inf
};

struct AovSettings {
    int width = 0;
    int height = 0;
    int spp = 1;  // jittered samples averaged per pixel
    uint64_t seed = 0;
};

// Renders the AOV; pixels are processed in parallel and the result does not depend on the
// number of threads. Medium boundaries without a surface are looked through.
Image render_aov(const Scene& scene, const Bvh& bvh, Aov aov, const AovSettings& settings);

}  // namespace wavetrace
