#include "wavetrace/scene/background.h"

#include <algorithm>
#include <cmath>

#include "math/equal_area.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

Vec2 environment_uv(const Background& bg, Vec3 w) {
    if (bg.frame) w = bg.frame->to_local(w);
    if (bg.mapping == Background::Mapping::EqualArea) {
        const Vec2 uv = equal_area_sphere_to_square(w);
        // [0, 1) as the other mapping: the square's far edges are its texels' inner borders.
        return {std::min(uv.x, 0x1.fffffep-1f), std::min(uv.y, 0x1.fffffep-1f)};
    }
    float phi = std::atan2(w.x, -w.z) - radians(bg.rotation);
    float theta = std::acos(std::clamp(w.y, -1.0f, 1.0f));
    float u = 0.5f + phi * (0.5f * kInvPi);
    return {u - std::floor(u), theta * kInvPi};
}

Vec3 environment_direction(const Background& bg, float u, float row) {
    Vec3 w;
    if (bg.mapping == Background::Mapping::EqualArea) {
        w = equal_area_square_to_sphere(u, row);
    } else {
        float phi = (u - 0.5f) * 2.0f * kPi + radians(bg.rotation);
        float theta = row * kPi;
        float sin_theta = std::sin(theta);
        w = {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
    }
    return bg.frame ? bg.frame->to_world(w) : w;
}

float environment_jacobian(const Background& bg, float row) {
    if (bg.mapping == Background::Mapping::EqualArea) return 4.0f * kPi;
    return 2.0f * kPi * kPi * std::sin(kPi * row);
}

Color eval_background(const Scene& scene, Vec3 d) {
    const Background& bg = scene.background;
    if (bg.kind == Background::Kind::Constant) return bg.radiance;
    Vec2 uv = environment_uv(bg, normalize(d));
    const ImageData& image = scene.images[bg.image];
    if (bg.mapping == Background::Mapping::EqualArea) {
        const int x = std::min(static_cast<int>(uv.x * image.width), image.width - 1);
        const int y = std::min(static_cast<int>(uv.y * image.height), image.height - 1);
        return bg.radiance * image.texel(x, y);
    }
    if (bg.rows_at_poles) {  // bilinear() puts row j at (j + 0.5) / H: move row to match
        const float h = static_cast<float>(image.height);
        uv.y = (uv.y * (h - 1.0f) + 0.5f) / h;
    }
    // bilinear() takes v bottom-to-top.
    return bg.radiance * image.bilinear(uv.x, 1.0f - uv.y, /*wrap_v=*/false);
}

}  // namespace wavetrace
