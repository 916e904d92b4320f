#include "wavetrace/shading/surface.h"

#include "scene/hit_geometry.h"
#include "scene/hit_hash.h"
#include "scene/material_lookup.h"
#include "scene/surface_point-inl.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane, lanes::to_lanes, lanes::to_vec3;

SurfaceHit surface_at(const Scene& scene, const Ray& ray, const Hit& hit) {
    SurfaceHit s;
    s.p = ray.at(hit.t);
    uint32_t i = hit.prim.index();
    switch (hit.prim.kind()) {
        case PrimKind::Triangle: {
            const Triangle& tri = scene.triangles[i];
            const Mesh& mesh = scene.meshes[tri.mesh];
            const lanes::V3<float> p[3] = {to_lanes(scene.positions[tri.v[0]]),
                                           to_lanes(scene.positions[tri.v[1]]),
                                           to_lanes(scene.positions[tri.v[2]])};
            lanes::V3<float> n[3] = {};
            if (mesh.has_normals)
                for (int k = 0; k < 3; ++k) n[k] = to_lanes(scene.normals[tri.v[k]]);
            const lanes::SurfacePoint<OneLane> sp =
                lanes::TrianglePoint<OneLane>(p, n, mesh.has_normals, hit.u, hit.v);
            s.p = to_vec3(sp.p);
            s.ng = to_vec3(sp.ng);
            s.ns = to_vec3(sp.ns);
            s.uv = hit_uv(scene, hit.prim, hit.u, hit.v, s.p);
            s.triangle = i;
            s.b1 = hit.u;
            s.b2 = hit.v;
            s.material = mesh.material;
            s.interior = mesh.interior;
            break;
        }
        case PrimKind::Quad: {
            const Quad& q = scene.quads[i];
            const lanes::SurfacePoint<OneLane> sp = lanes::QuadPoint<OneLane>(
                to_lanes(q.q), to_lanes(q.u), to_lanes(q.v), hit.u, hit.v);
            s.p = to_vec3(sp.p);
            s.ng = s.ns = to_vec3(sp.ng);
            s.uv = {hit.u, q.flip_v ? 1.0f - hit.v : hit.v};
            s.material = q.material;
            s.interior = q.interior;
            break;
        }
        case PrimKind::Sphere: {
            const Sphere& sp = scene.spheres[i];
            s.ng = s.ns = to_vec3(
                lanes::SpherePoint<OneLane>(to_lanes(s.p), to_lanes(sp.center), sp.radius).ng);
            // sphere_uv: an acos and an atan2 (7% of a render of spheres lit by spheres), so only
            // where a texture or a map of the sphere's material reads it.
            if (sp.material != kNone && material_reads_uv(scene, scene.materials[sp.material])) {
                s.uv = sphere_uv(scene, sp, s.ng);
            }
            s.material = sp.material;
            s.interior = sp.interior;
            break;
        }
    }
    // A blend becomes one of its materials here, where both engines and every walk of a ray
    // meet the hit, so that all that follows sees one material.
    if (s.material != kNone && scene.materials[s.material].kind == MaterialKind::Blend)
        s.material = blend_choice(scene, s.material, s.texture_point(),
                                  hit_hash(ray, hit.prim, HitDecision::Blend));
    if (s.material != kNone && scene.materials[s.material].needs_tangents()) {
        const Tangents t = hit_tangents(scene, hit.prim, s.p);
        s.dpdu = t.dpdu;
        s.dpdv = t.dpdv;
    }
    s.front_face = dot(ray.d, s.ng) < 0.0f;
    // Keep the shading normal on the geometric normal's side (interpolation can flip it).
    if (dot(s.ns, s.ng) < 0.0f) s.ns = -s.ns;
    return s;
}

}  // namespace wavetrace
