#include "wavetrace/scene/background.h"

#include <cmath>

#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

Color eval_background(const Scene& scene, Vec3 d) {
    const Background& bg = scene.background;
    if (bg.kind == Background::Kind::Constant) return bg.radiance;
    Vec3 w = normalize(d);
    float phi = std::atan2(w.x, -w.z) - radians(bg.rotation);
    float theta = std::acos(std::fmax(-1.0f, std::fmin(1.0f, w.y)));
    float u = 0.5f + phi * (0.5f * kInvPi);
    float v = 1.0f - theta * kInvPi;  // bilinear() takes v bottom-to-top
    return bg.radiance * scene.images[bg.image].bilinear(u, v, /*wrap_v=*/false);
}

}  // namespace wavetrace
