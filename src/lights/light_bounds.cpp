#include "lights/light_bounds.h"

#include <algorithm>
#include <cmath>

#include "scene/delta_lights.h"
#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

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

LightBounds union_of(std::span<const LightBounds> members) {
    if (members.size() == 1) return members[0];
    Vec3 lo{kInfinity}, hi{-kInfinity};
    for (const LightBounds& m : members)
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], m.centre[a] - m.radius);
            hi[a] = std::max(hi[a], m.centre[a] + m.radius);
        }
    LightBounds u = members[0];
    u.centre = 0.5f * (lo + hi);
    u.radius = 0.0f;
    u.phi = 0.0f;
    for (const LightBounds& m : members) {
        u.radius = std::max(u.radius, length(m.centre - u.centre) + m.radius);
        u.phi += m.phi;
        const bool same_cone = m.cos_theta_o == u.cos_theta_o && m.cos_theta_e == u.cos_theta_e &&
                               m.two_sided == u.two_sided && dot(m.axis, u.axis) >= 0.9999f;
        if (!same_cone) {
            u.cos_theta_o = -1.0f;
            u.sin_theta_o = 0.0f;
            u.cos_theta_e = 0.0f;
        }
    }
    return u;
}

LightBoundsColumns light_bounds_columns(std::span<const LightBounds> bounds, size_t padded) {
    LightBoundsColumns c;
    LightBounds none;
    none.phi = 0.0f;
    for (size_t k = 0; k < std::max(bounds.size(), padded); ++k) {
        const LightBounds& b = k < bounds.size() ? bounds[k] : none;
        for (int a = 0; a < 3; ++a) {
            c.centre[a].push_back(b.centre[a]);
            c.axis[a].push_back(b.axis[a]);
        }
        c.radius2.push_back(b.radius * b.radius);
        c.cos_o.push_back(b.cos_theta_o);
        c.sin_o.push_back(b.sin_theta_o);
        c.cos_e.push_back(b.cos_theta_e);
        c.two_sided.push_back(b.two_sided ? 1.0f : 0.0f);
        c.phi.push_back(b.phi);
        c.kind.push_back(static_cast<float>(b.kind));
    }
    return c;
}

}  // namespace wavetrace
