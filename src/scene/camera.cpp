#include "wavetrace/scene/camera.h"

#include <algorithm>
#include <cmath>

#include "scene/camera_ray-inl.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {

// The camera of Ray Tracing in One Weekend (§12-13): a film on the focus plane, rays from a disk
// lens; or an orthographic one's film at the eye.
CameraRays::CameraRays(const Camera& camera, int width, int height) {
    float focus = camera.focus_distance > 0 ? camera.focus_distance
                                            : length(camera.look_at - camera.look_from);
    float h = std::tan(radians(camera.vfov) * 0.5f);
    float view_h = 2.0f * h * focus;
    float view_w = view_h * (static_cast<float>(width) / static_cast<float>(height));

    Vec3 w = normalize(camera.look_from - camera.look_at);  // backwards
    Vec3 u = normalize(cross(camera.up, w));                // right
    Vec3 v = cross(w, u);                                   // up
    if (camera.mirror) u = -u;

    if (camera.orthographic) {
        // The film at look_from itself, rays along -w.
        view_h = camera.view_height;
        view_w = camera.view_width > 0.0f
                     ? camera.view_width
                     : view_h * (static_cast<float>(width) / static_cast<float>(height));
        focus = 0.0f;
        frame_.parallel = -w;
    }
    frame_.origin = camera.look_from;
    frame_.du = u * (view_w / static_cast<float>(width));
    frame_.dv = -v * (view_h / static_cast<float>(height));
    frame_.pixel00 = frame_.origin - focus * w - 0.5f * view_w * u + 0.5f * view_h * v;
    float lens_radius = 0.5f * camera.aperture;
    frame_.lens_u = u * lens_radius;
    frame_.lens_v = v * lens_radius;
    frame_.filter = camera.filter;
    // Kept below 1 so that the inverse error function stays finite at its ends.
    frame_.filter_erf = std::min(
        static_cast<float>(std::erf(camera.filter.radius / (camera.filter.sigma * std::sqrt(2.0)))),
        0.99999988f);
}

Ray CameraRays::generate(float x, float y, float lens_u, float lens_v) const {
    namespace lanes = HWY_NAMESPACE;
    lanes::V3<float> o, d;
    lanes::CameraRay<lanes::OneLane>(frame_, x, y, lens_u, lens_v, &o, &d);
    return Ray{lanes::to_vec3(o), lanes::to_vec3(d)};
}

}  // namespace wavetrace
