#include "wavetrace/scene/camera.h"

#include <cmath>

#include "wavetrace/math/constants.h"

namespace wavetrace {

// The seed's camera (RTIOW §12-13): a film on the focus plane, rays from a disk lens.
CameraRays::CameraRays(const Camera& camera, int width, int height) {
    float focus = camera.focus_distance > 0 ? camera.focus_distance
                                            : length(camera.look_at - camera.look_from);
    float h = std::tan(radians(camera.vfov) * 0.5f);
    float view_h = 2.0f * h * focus;
    float view_w = view_h * (static_cast<float>(width) / static_cast<float>(height));

    Vec3 w = normalize(camera.look_from - camera.look_at);  // backwards
    Vec3 u = normalize(cross(camera.up, w));                // right
    Vec3 v = cross(w, u);                                   // up

    origin_ = camera.look_from;
    du_ = u * (view_w / static_cast<float>(width));
    dv_ = -v * (view_h / static_cast<float>(height));
    pixel00_ = origin_ - focus * w - 0.5f * view_w * u + 0.5f * view_h * v;
    float lens_radius = 0.5f * camera.aperture;
    lens_u_ = u * lens_radius;
    lens_v_ = v * lens_radius;
}

Ray CameraRays::generate(float x, float y, float lens_u, float lens_v) const {
    Point3 target = pixel00_ + x * du_ + y * dv_;
    Point3 o = origin_;
    if (lens_u_.x != 0 || lens_u_.y != 0 || lens_u_.z != 0) {
        // Uniform point on the unit disk by the polar map (r = sqrt(u1), phi = 2 pi u2).
        float r = std::sqrt(lens_u), phi = 2.0f * kPi * lens_v;
        o += r * std::cos(phi) * lens_u_ + r * std::sin(phi) * lens_v_;
    }
    return Ray{o, target - o};
}

}  // namespace wavetrace
