#pragma once

#include "wavetrace/accel/bvh.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/ids.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

struct Scene;

// Everything shading needs about a ray's hit point.
struct SurfaceHit {
    Point3 p;
    Normal3 ng;              // geometric normal, unit, on the shape's outside (front)
    Normal3 ns;              // shading normal, unit, on the same side as ng
    Vec2 uv;                 // texture coordinates (spheres: only where a texture reads them)
    // dp/du, dp/dv where the material has a normal or bump map (scene/hit_geometry.h); else 0.
    Vec3 dpdu{0.0f}, dpdv{0.0f};
    // On a triangle (kNone: elsewhere), which, and the hit's barycentric coordinates of its
    // second and third vertex, for mesh attributes.
    uint32_t triangle = kNone;
    float b1 = 0.0f, b2 = 0.0f;
    bool front_face = true;  // the ray arrived from the side ng points to
    MaterialId material = kNone;
    MediumId interior = kNone;

    // Where its textures are looked up.
    TexturePoint texture_point() const { return {uv, p, triangle, b1, b2}; }
};

SurfaceHit surface_at(const Scene& scene, const Ray& ray, const Hit& hit);

}  // namespace wavetrace
