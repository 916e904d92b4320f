#include "wavetrace/scene/background.h"

#include <algorithm>
#include <cmath>

#include "scene/environment-inl.h"
#include "scene/environment_view.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

namespace lanes = HWY_NAMESPACE;
using lanes::OneLane;

EnvironmentView environment_view(const Background& bg, const ImageData& image) {
    static_assert(sizeof(Color) == 3 * sizeof(float));
    EnvironmentView e;
    e.texels = image.texels.empty() ? nullptr : &image.texels[0].x;
    e.width = image.width;
    e.height = image.height;
    e.equal_area = bg.mapping == Background::Mapping::EqualArea;
    e.rows_at_poles = bg.rows_at_poles;
    e.rotation = bg.rotation / 360.0f;
    if (bg.frame) {
        e.framed = true;
        for (int a = 0; a < 3; ++a) {
            e.frame[0][a] = bg.frame->s[a];
            e.frame[1][a] = bg.frame->t[a];
            e.frame[2][a] = bg.frame->n[a];
        }
    }
    return e;
}

EnvironmentView environment_view(const Scene& scene) {
    const Background& bg = scene.background;
    EnvironmentView e = environment_view(bg, scene.images[bg.image]);
    for (int c = 0; c < 3; ++c) e.scale[c] = bg.radiance[c];
    return e;
}

Vec2 environment_uv(const Background& bg, Vec3 w) {
    EnvironmentView e = environment_view(bg, ImageData{});
    Vec2 uv;
    lanes::EnvironmentUv<OneLane>(e, lanes::to_lanes(w), &uv.x, &uv.y);
    return uv;
}

Vec3 environment_direction(const Background& bg, float u, float row) {
    float jacobian;
    return lanes::to_vec3(
        lanes::EnvironmentDirection<OneLane>(environment_view(bg, ImageData{}), u, row, &jacobian));
}

float environment_jacobian(const Background& bg, float row) {
    return lanes::EnvironmentJacobian<OneLane>(environment_view(bg, ImageData{}), row);
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
    const EnvironmentView e = environment_view(scene);
    float u, v;
    lanes::EnvironmentUv<OneLane>(e, lanes::to_lanes(normalize(d)), &u, &v);
    return lanes::to_vec3(lanes::EnvironmentRadiance<OneLane>(e, u, v));
}

}  // namespace wavetrace
