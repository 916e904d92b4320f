#include "scene/delta_lights.h"

#include <algorithm>
#include <cmath>

#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {
namespace {

float spot_falloff(const Light& l, float cos_theta) {
    const float cos_cutoff = std::cos(radians(l.cutoff_degrees));
    const float cos_start = std::cos(radians(l.falloff_start_degrees));
    if (cos_theta <= cos_cutoff) return 0.0f;
    if (cos_theta >= cos_start) return 1.0f;
    if (l.falloff == Light::Falloff::Smoothstep) {
        const float t = (cos_theta - cos_cutoff) / (cos_start - cos_cutoff);
        return t * t * (3.0f - 2.0f * t);
    }
    const float theta = std::acos(std::clamp(cos_theta, -1.0f, 1.0f));
    return (radians(l.cutoff_degrees) - theta) /
           (radians(l.cutoff_degrees) - radians(l.falloff_start_degrees));
}

// Where a light's texture is looked up along unit d (d . axis > 0): the frustum of half extents
// (half_width, half_height) at unit distance spans [0, 1]^2, upright (Light::texture).
Vec2 frustum_uv(const Light& l, Vec3 d, float half_width, float half_height) {
    const float z = dot(d, l.direction);
    return {0.5f + dot(d, cross(l.direction, l.up)) / (2.0f * z * half_width),
            0.5f + dot(d, l.up) / (2.0f * z * half_height)};
}

}  // namespace

Color delta_light_intensity(const Scene& scene, const Light& l, Vec3 d) {
    switch (l.kind) {
        case Light::Kind::Point:
            return l.intensity;
        case Light::Kind::Spot: {
            const float falloff = spot_falloff(l, dot(d, l.direction));
            if (l.texture == kNone || falloff <= 0.0f) return l.intensity * falloff;
            // The square the cutoff cone is inscribed in.
            const float t = std::tan(radians(l.cutoff_degrees));
            return l.intensity * falloff *
                   eval_texture(scene, l.texture, frustum_uv(l, d, t, t), l.position);
        }
        case Light::Kind::Projector: {
            const float z = dot(d, l.direction);
            if (!(z > 0.0f)) return Color(0.0f);
            const Vec2 uv = frustum_uv(l, d, l.half_width, l.half_height);
            if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) return Color(0.0f);
            const Color t =
                l.texture == kNone ? Color(1.0f) : eval_texture(scene, l.texture, uv, l.position);
            return l.projects_intensity ? l.intensity * t : l.intensity * t * (kPi / (z * z * z));
        }
        case Light::Kind::Directional:
            break;
    }
    return Color(0.0f);
}

float delta_light_power(const Scene& scene, const Light& l, float scene_radius) {
    const float lum = luminance(l.intensity);
    switch (l.kind) {
        case Light::Kind::Point:
            return 4.0f * kPi * lum;
        case Light::Kind::Spot: {
            // Full within the falloff start, about half across the falloff (pbrt-v4's Phi).
            const float cos_start = std::cos(radians(l.falloff_start_degrees));
            const float cos_cutoff = std::cos(radians(l.cutoff_degrees));
            return 2.0f * kPi * lum * ((1.0f - cos_start) + 0.5f * (cos_start - cos_cutoff));
        }
        case Light::Kind::Projector: {
            const float mean_texture =
                l.texture == kNone ? 1.0f : luminance(texture_mean(scene, l.texture));
            // Mitsuba's: pi I t over the frustum's area at unit distance (cos^3 is the solid
            // angle's dA); pbrt's: I t over the frustum's solid angle, that of a rectangular
            // pyramid, 4 asin(w h / sqrt((1 + w^2) (1 + h^2))).
            const float w = l.half_width, h = l.half_height;
            return l.projects_intensity
                       ? lum * mean_texture * 4.0f *
                             std::asin(w * h / std::sqrt((1.0f + w * w) * (1.0f + h * h)))
                       : kPi * lum * mean_texture * 4.0f * w * h;
        }
        case Light::Kind::Directional:
            return kPi * scene_radius * scene_radius * lum;
    }
    return 0.0f;
}

}  // namespace wavetrace
