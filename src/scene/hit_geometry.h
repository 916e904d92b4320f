// Where on a primitive a hit lies, from the intersector's parameters (u, v) (barycentrics b1,
// b2 of a triangle, the quad's edge parameters; unused for spheres) and the hit point p: its
// texture coordinates, and the surface's derivatives along them (which depend on the point
// alone) for normal and bump maps.
#pragma once

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct Scene;

Vec2 hit_uv(const Scene& scene, PrimRef prim, float u, float v, Point3 p);

// dp/du and dp/dv, the change of the point with the texture coordinates: a triangle's from its
// vertices' positions and uvs (pbrt-v4's Triangle::InteractionFromIntersection; without uvs,
// or with degenerate ones, along the edges v0->v1 and v0->v2), a quad's its edges, a sphere's
// from its mapping (texture.h's sphere_uv). Zero where the mapping has none (a sphere's poles).
struct Tangents {
    Vec3 dpdu{0.0f}, dpdv{0.0f};
};
Tangents hit_tangents(const Scene& scene, PrimRef prim, Point3 p);

}  // namespace wavetrace
