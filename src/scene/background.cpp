#include "wavetrace/scene/background.h"

#include <algorithm>
#include <cmath>

#include "math/equal_area.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

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

double environment_illuminance(const Background& bg, const ImageData& image) {
    const bool equal_area = bg.mapping == Background::Mapping::EqualArea;
    // Lat-long rows sit at their bands' centres, or on the poles with rows_at_poles (the end
    // rows then carry no solid angle); columns are centred either way.
    const bool at_poles = !equal_area && bg.rows_at_poles && image.height > 1;
    const double dv = at_poles ? 1.0 / (image.height - 1) : 1.0 / image.height;
    const double du = 1.0 / image.width;
    Background own = bg;
    own.frame.reset();
    double sum = 0.0;
    for (int y = 0; y < image.height; ++y) {
        const float row = static_cast<float>(at_poles ? y * dv : (y + 0.5) * dv);
        const double jacobian = environment_jacobian(own, row);
        for (int x = 0; x < image.width; ++x) {
            const Vec3 w = environment_direction(own, static_cast<float>((x + 0.5) * du), row);
            const double cos_theta = equal_area ? w.z : w.y;
            if (cos_theta > 0) sum += luminance(image.texel(x, y)) * cos_theta * jacobian;
        }
    }
    return sum * du * dv;
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
