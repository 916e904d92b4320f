#pragma once

#include <cstdint>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

// A light that is not a shape: a Dirac delta in position (point, spot, projector) or in
// direction (directional). No ray can hit one, so only next-event estimation (strategies nee and
// mis) reaches it, as in pbrt-v4 and Mitsuba 3.
struct Light {
    enum class Kind : uint8_t {
        Point,        // radiant intensity `intensity` (W sr^-1 per channel) in every direction
        Spot,         // the same within a cone about `direction`, with a falloff towards its edge
        Directional,  // parallel light travelling along `direction`: irradiance `intensity`
                      // (W m^-2 per channel) on a surface facing it
        Projector,    // Mitsuba 3's projector: a pinhole projecting `texture` (or white) through
                      // a rectangular frustum about `direction`; a white Lambertian plane at
                      // unit distance across the axis shows radiance `intensity` x texture
                      // (intensity pi `intensity` texture / cos^3 theta, theta from the axis),
                      // or with projects_intensity pbrt-v4's projection light (intensity
                      // `intensity` texture)
    };
    // How a spot light's intensity falls from the falloff start to the cutoff.
    enum class Falloff : uint8_t {
        Linear,      // linearly in the angle (Mitsuba 3's spot)
        Smoothstep,  // smoothstep in the cosine (pbrt-v4's spotlight)
    };
    Kind kind = Kind::Point;
    Point3 position;  // point, spot
    Vec3 direction{0.0f, 0.0f,
                   -1.0f};  // spot: the cone's axis; directional: where light goes; unit
    Color intensity{0.0f};
    float cutoff_degrees = 20.0f;         // spot: the half-angle beyond which it is dark
    float falloff_start_degrees = 15.0f;  // spot: the half-angle within which it is full
    Falloff falloff = Falloff::Linear;
    // spot: a texture it projects, like a slide projector (kNone: none). Its intensity towards
    // direction d is multiplied by the texture at
    //   u = 1/2 + (d . right) / (2 (d . axis) tan cutoff),
    //   v = 1/2 + (d . up) / (2 (d . axis) tan cutoff),
    // right = axis x up: seen from the light looking along its axis, the image stands upright
    // with `up` towards its top and spans the square that the cutoff cone is inscribed in.
    // A projector's texture is looked up at (1/2 + (d . right) / (2 (d . axis) half_width),
    // 1/2 + (d . up) / (2 (d . axis) half_height)): its frustum, as a spot's, upright.
    TextureId texture = kNone;
    Vec3 up{0.0f, 1.0f, 0.0f};  // spot with a texture, projector: unit, orthogonal to `direction`
    // projector: the frustum's half extents at unit distance along the axis (tangents).
    float half_width = 1.0f, half_height = 1.0f;
    // projector: `intensity` x texture is the intensity itself, the same towards every texel
    // (pbrt-v4's projection light), rather than Mitsuba's irradiance at unit distance.
    bool projects_intensity = false;

    // A point light of `intensity` at `position`.
    static Light point(Point3 position, Color intensity) {
        Light l;
        l.position = position;
        l.intensity = intensity;
        return l;
    }
};

}  // namespace wavetrace
