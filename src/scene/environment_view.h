// An environment map as the lane formulas read it (scene/environment-inl.h): its texels, scale
// and mapping, gathered from a Scene's Background once, so that a lookup reads plain fields.
#pragma once

#include "wavetrace/scene/background.h"

namespace wavetrace {

struct Scene;

struct EnvironmentView {
    const float* texels = nullptr;  // RGB per texel, row-major, row 0 at the top
    int width = 0, height = 0;
    float scale[3] = {1.0f, 1.0f, 1.0f};  // Background::radiance, per channel
    bool equal_area = false;              // Background::Mapping::EqualArea, else lat-long
    bool rows_at_poles = false;           // Background::rows_at_poles
    float rotation = 0.0f;                // lat-long: Background::rotation, in turns
    bool framed = false;                  // Background::frame: its axes s, t, n as rows
    float frame[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
};

// The view of scene.background, which must be an environment map.
EnvironmentView environment_view(const Scene& scene);
// The same for background bg looking up `image`, at unit scale (Background::radiance ignored).
EnvironmentView environment_view(const Background& bg, const ImageData& image);

}  // namespace wavetrace
