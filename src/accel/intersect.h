// Ray-primitive intersection for the three primitive kinds the BVH holds. Shared by the
// BVH traversal and by tests; each returns false or fills t and two surface parameters.
#pragma once

#include "wavetrace/math/ray.h"
#include "wavetrace/scene/shapes.h"

namespace wavetrace {

struct PrimHit {
    float t;
    float u, v;  // triangle: barycentrics of v1 and v2; quad: (alpha, beta); sphere: unused
};

// Nearest root in [ray.tmin, ray.tmax] of |o + t d - c| = r, computed with the
// cancellation-free discriminant of Haines et al., "Precision Improvements for Ray/Sphere
// Intersection", Ray Tracing Gems ch. 7 (2019). A ray starting inside hits the far side.
bool intersect_sphere(const Ray& ray, Point3 center, float radius, PrimHit* hit);

// The quad test of Ray Tracing: The Next Week: hit the plane, then express the point in the (u, v) basis.
// Edges are inclusive on both sides so that rays through the shared edge of two adjacent
// quads hit at least one of them.
bool intersect_quad(const Ray& ray, Point3 q, Vec3 u, Vec3 v, PrimHit* hit);

// Watertight ray/triangle test: Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), 2013 (edge functions in float, recomputed in double when one is
// exactly 0), with pbrt-v4's conservative bound that t is above zero.
// Rays through a shared edge or vertex of a closed mesh hit at least one of its triangles.
bool intersect_triangle(const Ray& ray, Point3 p0, Point3 p1, Point3 p2, PrimHit* hit);

// The per-ray part of that test, computed once per ray and reused for every triangle it meets
// (Woop et al. §3): the axis permutation that makes the direction's largest component z, and
// the shear that aligns the ray with +z.
struct TriangleRay {
    Point3 o;
    int kx, ky, kz;
    float sx, sy, sz;
    // Inline: it runs once per traced ray. One division: the shear uses 1 / d_z.
    explicit TriangleRay(const Ray& ray) : o(ray.o) {
        kz = max_dimension(abs(ray.d));
        kx = kz + 1 == 3 ? 0 : kz + 1;
        ky = kx + 1 == 3 ? 0 : kx + 1;
        sz = 1.0f / ray.d[kz];
        sx = -ray.d[kx] * sz;
        sy = -ray.d[ky] * sz;
    }
};
// The same test with the per-ray part precomputed; hits lie in [tmin, tmax].
bool intersect_triangle(
    const TriangleRay& r, float tmin, float tmax, Point3 p0, Point3 p1, Point3 p2, PrimHit* hit);

}  // namespace wavetrace
