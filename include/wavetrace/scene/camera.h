#pragma once

#include "wavetrace/math/ray.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// The reconstruction filter of the film's pixels, sampled by importance (filter importance
// sampling, Ernst et al. 2006, as pbrt-v4 does): a sample's ray leaves from an offset about its
// pixel's centre distributed as the filter, and it counts in its own pixel with weight 1, so a
// film stays a sum of unit-weight samples (resume, split and merge stay exact).
struct PixelFilter {
    enum class Kind : uint8_t {
        Box,       // uniform over [-radius, radius]^2 (radius 0.5: the pixel itself)
        Tent,      // (radius - |x|)(radius - |y|), pbrt's "triangle", Mitsuba's "tent"
        Gaussian,  // exp(-(x^2 + y^2) / (2 sigma^2)) truncated to [-radius, radius]^2
    };
    Kind kind = Kind::Box;
    float radius = 0.5f;  // in pixels
    float sigma = 0.5f;   // Gaussian: the standard deviation, in pixels
};

// A thin-lens camera as in the seed (RTIOW §12-13). With aperture 0 it is a pinhole. Or an
// orthographic camera (Mitsuba 3's and pbrt-v4's `orthographic`): parallel rays along the view
// direction from a film of view_width x view_height world units centred on look_from.
struct Camera {
    Point3 look_from{0.0f, 0.0f, 0.0f};
    Point3 look_at{0.0f, 0.0f, -1.0f};
    Vec3 up{0.0f, 1.0f, 0.0f};
    float vfov = 40.0f;           // vertical field of view, degrees
    float aperture = 0.0f;        // lens diameter, world units
    float focus_distance = 0.0f;  // 0: the distance from look_from to look_at
    bool orthographic = false;
    float view_height = 2.0f;  // orthographic: the film's height in world units
    float view_width = 0.0f;   // ... and width (0: view_height times the image's aspect)
    // The image's x axis reversed (a left-handed camera frame, as pbrt's): the image's right
    // is cross(w, up) instead of cross(up, w), w pointing backwards.
    bool mirror = false;
    PixelFilter filter;
};

// What maps film positions to rays, for one film size.
struct CameraFrame {
    Point3 origin;
    Point3 pixel00;       // the top-left corner of the film on the focus plane
    Vec3 du, dv;          // one pixel to the right / down, on the focus plane
    Vec3 lens_u, lens_v;  // lens radius times the camera's right / up axes
    // Orthographic: the view direction, every ray's (the film then lies at look_from); zero for
    // a perspective camera.
    Vec3 parallel{0.0f};
    PixelFilter filter;
    float filter_erf = 0.0f;  // Gaussian: erf(radius / (sigma sqrt 2)), the mass it keeps
    bool has_lens() const { return lens_u.x != 0 || lens_u.y != 0 || lens_u.z != 0; }
    bool orthographic() const { return parallel.x != 0 || parallel.y != 0 || parallel.z != 0; }
};

// A camera set up for one film size: maps film positions to rays.
class CameraRays {
  public:
    CameraRays(const Camera& camera, int width, int height);

    // Ray through film position (x, y) in pixels (0,0 is the top-left corner of the image,
    // x to the right, y down); (lens_u, lens_v) in [0,1)^2 pick the point on the lens.
    // The direction is not normalized. The one-lane instance of CameraRay
    // (src/scene/camera_ray-inl.h), which the wavefront's generate kernel runs in SIMD lanes.
    Ray generate(float x, float y, float lens_u, float lens_v) const;
    const CameraFrame& frame() const { return frame_; }

  private:
    CameraFrame frame_;
};

}  // namespace wavetrace
