// What a light could send to a point, bounded cheaply, for choosing which light a vertex
// samples: the light bounds of pbrt-v4 (Pharr, Jakob and Humphreys, "Physically Based
// Rendering", 4th ed., §12.6.3, after Conty Estevez and Kulla, "Importance Sampling of Many
// Lights with Adaptive Tree Splitting", 2018). A light lies within a sphere and emits within a
// cone of directions; its importance at a point is its emitted radiance times area (or its
// intensity) over the squared distance, times the cosines at the light and at the point, each
// relaxed by the angle the sphere subtends — an estimate of the irradiance it brings, never
// zero where it can bring any.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct LightBounds {
    enum class Kind : uint8_t {
        Bounded,      // within the sphere (centre, radius), emitting within the cone
        Directional,  // parallel light travelling along `axis`: irradiance `phi`
        Background,   // light from every direction, of mean radiance `phi`
    };
    Kind kind = Kind::Bounded;
    Point3 centre;
    float radius = 0.0f;  // 0: a point
    // Bounded: emitted directions lie within theta_o of axis (cos_theta_o -1: every
    // direction), and past theta_o the emission falls to zero within theta_e more (cos_theta_e
    // 0: a Lambertian face, 1: none past theta_o); two_sided: about -axis as well.
    Vec3 axis{0.0f, 0.0f, 1.0f};
    float cos_theta_o = -1.0f, sin_theta_o = 0.0f;
    float cos_theta_e = 0.0f;
    bool two_sided = false;
    // Luminance: a face's radiance times its area, a sphere's radiance times pi r^2, a point's
    // or spot's intensity; a directional light's irradiance, a background's mean radiance.
    float phi = 0.0f;
};

// The light's importance at point p with normal n (zero in a medium), computed in lanes
// (lights/light_importance-inl.h): for a bounded light phi cos(theta') / d^2 times the cosine
// at p (|cos|: the point may transmit), both angles less the angle its sphere subtends from p,
// and d^2 at least half the radius squared (so that A / d^2 stays below 2 pi); a directional
// light's phi |cos|; a background's pi phi at a surface, 4 pi phi in a medium (where a bounded
// light's has no cosine at p either). The cosine at p is at least 1/16, since a shading normal
// may see light the geometric normal grazes. Zero only where the light sends nothing: behind a
// one-sided face, outside a cone.

// LightBounds of several lights as columns, for the lanes: entry k light k, padded to a whole
// number of vectors with lights of importance zero.
struct LightBoundsColumns {
    std::vector<float> centre[3], axis[3], radius2, cos_o, sin_o, cos_e, two_sided, phi, kind;
    size_t size() const { return phi.size(); }
};
LightBoundsColumns light_bounds_columns(std::span<const LightBounds> bounds, size_t padded);

// Bounds that hold all of `members` (not empty): a sphere around theirs, the sum of their phi,
// and their common cone where they all face one way (a planar light's triangles), else every
// direction. Bounded lights only.
LightBounds union_of(std::span<const LightBounds> members);

struct Scene;
struct Light;

// An emissive quad, triangle or sphere of radiance luminance `luminance`: a face emits about
// its front normal (cross(u, v), as the light sampling takes it), or on both sides.
LightBounds emitter_bounds(const Scene& scene, PrimRef prim, float luminance, bool two_sided);
// A point, spot, projector or directional light (a projector's intensity the mean over the cone
// that holds its frustum, of its power at delta_light_power's scene radius).
LightBounds delta_light_bounds(const Scene& scene, const Light& l, float scene_radius);

}  // namespace wavetrace
