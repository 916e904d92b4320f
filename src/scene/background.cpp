#include "wavetrace/scene/background.h"

#include <algorithm>
#include <cmath>

#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

Vec2 environment_uv(const Background& bg, Vec3 w) {
    float phi = std::atan2(w.x, -w.z) - radians(bg.rotation);
    float theta = std::acos(std::clamp(w.y, -1.0f, 1.0f));
    float u = 0.5f + phi * (0.5f * kInvPi);
    return {u - std::floor(u), theta * kInvPi};
}

Vec3 environment_direction(const Background& bg, float u, float row) {
    float phi = (u - 0.5f) * 2.0f * kPi + radians(bg.rotation);
    float theta = row * kPi;
    float sin_theta = std::sin(theta);
    return {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
}

Color eval_background(const Scene& scene, Vec3 d) {
    const Background& bg = scene.background;
    if (bg.kind == Background::Kind::Constant) return bg.radiance;
    Vec2 uv = environment_uv(bg, normalize(d));
    const ImageData& image = scene.images[bg.image];
    if (bg.rows_at_poles) {  // bilinear() puts row j at (j + 0.5) / H: move row to match
        const float h = static_cast<float>(image.height);
        uv.y = (uv.y * (h - 1.0f) + 0.5f) / h;
    }
    // bilinear() takes v bottom-to-top.
    return bg.radiance * image.bilinear(uv.x, 1.0f - uv.y, /*wrap_v=*/false);
}

}  // namespace wavetrace
