// The shading steps that trace rays, generic over the intersector (our BVH, or Embree in the
// benchmarks) so that both engines call them with no virtual call per ray.
#pragma once

#include <cmath>
#include <optional>

#include "accel/intersector.h"
#include "media/medium_segment.h"
#include "shading/path_vertex.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/shading/surface.h"

namespace wavetrace {

// Whether a shadow ray passes surfaces of material m: medium boundaries, and thin sheets, which
// let 1 - R' through (sheet_transmittance). Passing a sheet is a null event for paths
// (path_vertex.h, next_depth); a shadow ray passes it too, as Mitsuba 3's volpath passes its
// thindielectric's Null lobe, so that light reaches a room through its window by next-event
// estimation, and a medium inside a sheet is lit by it.
inline bool shadows_pass(const Scene& scene, MaterialId m) {
    return m < scene.materials.size() && (scene.materials[m].kind == MaterialKind::Interface ||
                                          scene.materials[m].kind == MaterialKind::ThinDielectric);
}

// Whether shadow rays need more than an occlusion test (transmittance below): the scene has
// media or surfaces they pass. It reads every material: ask it once per render.
inline bool shadows_walk(const Scene& scene) {
    if (!scene.media.empty()) return true;
    for (MaterialId m = 0; m < scene.materials.size(); ++m)
        if (shadows_pass(scene, m)) return true;
    return false;
}

// transmittance (below) once an occlusion test has said what it stopped at (`any`, none if
// nothing): 0 for a surface, that of the one medium crossed for nothing at all, or none for a
// surface it passes, where only the closest-hit walk can tell.
inline std::optional<Color> transmittance_after_any_hit(const Scene& scene,
                                                        const Ray& ray,
                                                        const MediumStack& media,
                                                        const Hit& any) {
    if (any.found()) {
        if (shadows_pass(scene, scene.prim_material(any.prim))) return std::nullopt;
        return Color(0.0f);
    }
    const MediumId m = media.current();
    if (m == kNone) return Color(1.0f);
    return segment_transmittance(scene, m, ray, ray.tmin, ray.tmax);
}

// transmittance (below) by walking from closest hit to closest hit, stepping over the surfaces
// it passes.
template <Intersector Tracer>
Color transmittance_walk(
    const Scene& scene, const Tracer& bvh, Ray ray, MediumStack media, uint64_t* rays) {
    Color tr(1.0f);
    for (int crossing = 0; crossing < kMaxBoundaryCrossings; ++crossing) {
        ++*rays;
        Hit hit = bvh.intersect(ray);
        float end = hit.found() ? hit.t : ray.tmax;
        MediumId m = media.current();
        if (m != kNone) tr = tr * segment_transmittance(scene, m, ray, ray.tmin, end);
        if (max_component(tr) == 0.0f) return Color(0.0f);
        if (!hit.found()) return tr;
        // A surface blocks it; only one it passes needs the point, to step over it.
        const MaterialId material = scene.prim_material(hit.prim);
        if (!shadows_pass(scene, material)) return Color(0.0f);
        SurfaceHit s = surface_at(scene, ray, hit);
        if (scene.materials[material].kind == MaterialKind::ThinDielectric) {
            tr = tr * sheet_transmittance(scene, s, normalize(ray.d));
            if (max_component(tr) == 0.0f) return Color(0.0f);
        }
        // Into or out of its interior, as a path passing it goes (continue_path, cross_boundary).
        media.cross(s.interior, s.front_face, scene.medium_boundaries);
        ray.tmin = hit.t;
        // Step over the boundary: restart just past it along the same line.
        ray.o = ray.at(hit.t) + origin_offset(s.p) * normalize(ray.d);
        ray.tmax = std::isinf(ray.tmax) ? ray.tmax : ray.tmax - hit.t;
        ray.tmin = 0.0f;
    }
    return Color(0.0f);
}

// Fraction of light that gets through along a shadow ray, per channel: 0 if a surface blocks
// it, else the product of exp(-sigma_t * length) over the media it crosses and of 1 - R' over the thin
// sheets it passes (boundaries without a surface let it through). `media` is the stack at the
// ray's origin; `walks`, shadows_walk(scene). Counts the rays it traces.
template <Intersector Tracer>
Color transmittance(const Scene& scene,
                    const Tracer& bvh,
                    Ray ray,
                    MediumStack media,
                    bool walks,
                    uint64_t* rays) {
    if (!walks) {
        ++*rays;
        return Color(bvh.occluded(ray) ? 0.0f : 1.0f);
    }
    // Most shadow rays are blocked by a surface or cross no boundary at all: an occlusion test
    // that says what it stopped at (where the intersector has one) settles both without the
    // closest-hit walk, which only a ray that meets a surface it passes first needs.
    if constexpr (AnyHitIntersector<Tracer>) {
        ++*rays;
        if (const std::optional<Color> tr =
                transmittance_after_any_hit(scene, ray, media, bvh.any_hit(ray)))
            return *tr;
    }
    return transmittance_walk(scene, bvh, ray, media, rays);
}

// The media containing point p, found by walking a ray out of the scene and pairing the
// boundaries it enters and leaves (convex, properly nested boundaries assumed).
template <Intersector Tracer>
MediumStack media_at(const Scene& scene, const Tracer& bvh, Point3 p) {
    MediumStack outside_in;  // boundaries we are inside of, innermost first
    if (scene.media.empty()) return outside_in;
    // An arbitrary fixed direction, unlikely to graze axis-aligned geometry.
    Ray ray{p, normalize(Vec3{0.3141f, 0.2718f, 0.9093f})};
    int n_entered = 0;  // shapes entered on the way out, not yet left
    MediumId found[MediumStack::kMaxNesting];
    int n_found = 0;
    for (int i = 0; i < 256; ++i) {
        Hit hit = bvh.intersect(ray);
        if (!hit.found()) break;
        SurfaceHit s = surface_at(scene, ray, hit);
        const MaterialKind kind = scene.materials[s.material].kind;
        // A thin sheet bounds a medium only where it has one inside (a window pane does not).
        if (kind == MaterialKind::Interface || kind == MaterialKind::Dielectric ||
            (kind == MaterialKind::ThinDielectric && s.interior != kNone)) {
            if (s.front_face) {
                ++n_entered;
            } else if (n_entered > 0) {
                --n_entered;  // leaving a shape entered on the way
            } else if (n_found < MediumStack::kMaxNesting) {
                found[n_found++] = s.interior;  // leaving a shape p is inside of
            }
        }
        ray.o = ray.at(hit.t) + origin_offset(s.p) * ray.d;
        ray.tmin = 0.0f;
    }
    for (int i = n_found - 1; i >= 0; --i) outside_in.push(found[i]);
    return outside_in;
}

}  // namespace wavetrace
