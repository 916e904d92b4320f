#include "lights/light_bounds.h"

#include <algorithm>
#include <cmath>

#include "scene/delta_lights.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

namespace {

constexpr float kMinCosAtPoint = 1.0f / 16.0f;

float safe_sqrt(float x) {
    return std::sqrt(std::max(x, 0.0f));
}

// cos(max(a - b, 0)) from the cosines and sines of angles a and b in [0, pi].
float cos_of_difference(float cos_a, float sin_a, float cos_b, float sin_b) {
    return cos_a >= cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
// sin(max(a - b, 0)) likewise.
float sin_of_difference(float cos_a, float sin_a, float cos_b, float sin_b) {
    return cos_a >= cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

bool is_zero(Normal3 n) {
    return n.x == 0.0f && n.y == 0.0f && n.z == 0.0f;
}

}  // namespace

float light_importance(const LightBounds& b, Point3 p, Normal3 n) {
    const bool surface = !is_zero(n);
    switch (b.kind) {
        case LightBounds::Kind::Background:
            return (surface ? kPi : 4.0f * kPi) * b.phi;
        case LightBounds::Kind::Directional:
            return surface ? b.phi * std::max(std::fabs(dot(b.axis, n)), kMinCosAtPoint) : b.phi;
        case LightBounds::Kind::Bounded:
            break;
    }
    const Vec3 w = p - b.centre;  // from the light to the point
    const float d2 = length_squared(w);
    // The half-angle theta_b of the cone from p that holds the sphere (every direction from
    // inside it).
    const float r2 = b.radius * b.radius;
    float sin_b = 0.0f, cos_b = 1.0f;  // a point's
    if (r2 > 0.0f) {
        const float sin2_b = d2 > r2 ? r2 / d2 : 1.0f;
        sin_b = std::sqrt(sin2_b);
        cos_b = safe_sqrt(1.0f - sin2_b);
    }
    const float d = std::sqrt(d2);
    const Vec3 wn = d > 0.0f ? w / d : b.axis;

    // theta' = max(theta_w - theta_o - theta_b, 0), theta_w between the axis and w.
    float cos_p = 1.0f;
    if (b.cos_theta_o > -1.0f) {
        float cos_w = dot(b.axis, wn);
        if (b.two_sided) cos_w = std::fabs(cos_w);
        const float sin_w = safe_sqrt(1.0f - cos_w * cos_w);
        const float cos_x = cos_of_difference(cos_w, sin_w, b.cos_theta_o, b.sin_theta_o);
        const float sin_x = sin_of_difference(cos_w, sin_w, b.cos_theta_o, b.sin_theta_o);
        cos_p = cos_of_difference(cos_x, sin_x, cos_b, sin_b);
        if (cos_p < b.cos_theta_e) return 0.0f;
    }
    float importance = b.phi * cos_p / std::max({d2, 0.5f * r2, 1e-20f});
    if (surface) {
        const float cos_i = std::fabs(dot(n, wn));
        const float sin_i = safe_sqrt(1.0f - cos_i * cos_i);
        importance *= std::max(cos_of_difference(cos_i, sin_i, cos_b, sin_b), kMinCosAtPoint);
    }
    return std::max(importance, 0.0f);
}

LightBounds emitter_bounds(const Scene& scene, PrimRef prim, float luminance, bool two_sided) {
    LightBounds b;
    b.phi = luminance * scene.prim_area(prim);
    if (prim.kind() == PrimKind::Sphere) {
        const Sphere& s = scene.spheres[prim.index()];
        b.centre = s.center;
        b.radius = s.radius;
        b.phi = luminance * kPi * s.radius * s.radius;
        return b;
    }
    Point3 corners[4];
    int count = 3;
    if (prim.kind() == PrimKind::Quad) {
        const Quad& q = scene.quads[prim.index()];
        corners[0] = q.q;
        corners[1] = q.q + q.u;
        corners[2] = q.q + q.u + q.v;
        corners[3] = q.q + q.v;
        count = 4;
    } else {
        const Triangle& t = scene.triangles[prim.index()];
        for (int k = 0; k < 3; ++k) corners[k] = scene.positions[t.v[k]];
    }
    Vec3 sum{0.0f};
    for (int k = 0; k < count; ++k) sum = sum + corners[k];
    b.centre = sum / static_cast<float>(count);
    for (int k = 0; k < count; ++k) b.radius = std::max(b.radius, length(corners[k] - b.centre));
    const Vec3 n = cross(corners[1] - corners[0], corners[count - 1] - corners[0]);
    const float len = length(n);
    if (!(len > 0.0f)) return b;  // degenerate: every direction
    b.axis = n / len;
    b.cos_theta_o = 1.0f;
    b.sin_theta_o = 0.0f;
    b.cos_theta_e = 0.0f;
    b.two_sided = two_sided;
    return b;
}

LightBounds delta_light_bounds(const Scene& scene, const Light& l, float scene_radius) {
    LightBounds b;
    b.phi = luminance(l.intensity);
    b.centre = l.position;
    b.axis = l.direction;
    switch (l.kind) {
        case Light::Kind::Point:
            break;
        case Light::Kind::Directional:
            b.kind = LightBounds::Kind::Directional;
            break;
        case Light::Kind::Spot: {
            const float start = std::min(l.falloff_start_degrees, l.cutoff_degrees) * kPi / 180;
            b.cos_theta_o = std::cos(start);
            b.sin_theta_o = std::sin(start);
            b.cos_theta_e = std::cos(l.cutoff_degrees * kPi / 180 - start);
            break;
        }
        case Light::Kind::Projector: {
            const float tan_o =
                std::sqrt(l.half_width * l.half_width + l.half_height * l.half_height);
            b.cos_theta_o = 1.0f / std::sqrt(1.0f + tan_o * tan_o);
            b.sin_theta_o = tan_o * b.cos_theta_o;
            b.cos_theta_e = 1.0f;
            b.phi =
                delta_light_power(scene, l, scene_radius) / (2.0f * kPi * (1.0f - b.cos_theta_o));
            break;
        }
    }
    return b;
}

}  // namespace wavetrace
