#include "wavetrace/scene/surface.h"

#include <cmath>

#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

SurfaceHit surface_at(const Scene& scene, const Ray& ray, const Hit& hit) {
    SurfaceHit s;
    s.p = ray.at(hit.t);
    uint32_t i = hit.prim.index();
    switch (hit.prim.kind()) {
        case PrimKind::Triangle: {
            const Triangle& tri = scene.triangles[i];
            const Mesh& mesh = scene.meshes[tri.mesh];
            Point3 p0 = scene.positions[tri.v[0]], p1 = scene.positions[tri.v[1]],
                   p2 = scene.positions[tri.v[2]];
            float b1 = hit.u, b2 = hit.v, b0 = 1.0f - b1 - b2;
            // Interpolate the position from the vertices: more accurate than o + t d.
            s.p = b0 * p0 + b1 * p1 + b2 * p2;
            s.ng = normalize(cross(p1 - p0, p2 - p0));
            s.ns = s.ng;
            if (mesh.has_normals) {
                Normal3 n = b0 * scene.normals[tri.v[0]] + b1 * scene.normals[tri.v[1]] +
                            b2 * scene.normals[tri.v[2]];
                if (length_squared(n) > 0) s.ns = normalize(n);
            }
            if (mesh.has_uvs) {
                Vec2 t0 = scene.uvs[tri.v[0]], t1 = scene.uvs[tri.v[1]], t2 = scene.uvs[tri.v[2]];
                s.uv = {b0 * t0.x + b1 * t1.x + b2 * t2.x, b0 * t0.y + b1 * t1.y + b2 * t2.y};
            } else {
                s.uv = {b1, b2};
            }
            s.material = mesh.material;
            s.interior = mesh.interior;
            break;
        }
        case PrimKind::Quad: {
            const Quad& q = scene.quads[i];
            s.p = q.q + hit.u * q.u + hit.v * q.v;
            s.ng = s.ns = normalize(cross(q.u, q.v));
            s.uv = {hit.u, hit.v};
            s.material = q.material;
            s.interior = q.interior;
            break;
        }
        case PrimKind::Sphere: {
            const Sphere& sp = scene.spheres[i];
            s.ng = s.ns = (s.p - sp.center) / sp.radius;
            s.ng = s.ns = normalize(s.ng);
            // The seed's sphere mapping: u = phi / 2 pi around -x..+z.., v = theta / pi from -y.
            // An acos and an atan2 (7% of a render of spheres lit by spheres), so only where a
            // texture of the sphere's material reads it.
            if (sp.material != kNone &&
                (texture_reads_uv(scene, scene.materials[sp.material].albedo) ||
                 texture_reads_uv(scene, scene.materials[sp.material].emission))) {
                float theta = std::acos(std::fmax(-1.0f, std::fmin(1.0f, -s.ng.y)));
                float phi = std::atan2(-s.ng.z, s.ng.x) + kPi;
                s.uv = {phi * (0.5f * kInvPi), theta * kInvPi};
            }
            s.material = sp.material;
            s.interior = sp.interior;
            break;
        }
    }
    s.front_face = dot(ray.d, s.ng) < 0.0f;
    // Keep the shading normal on the geometric normal's side (interpolation can flip it).
    if (dot(s.ns, s.ng) < 0.0f) s.ns = -s.ns;
    return s;
}

}  // namespace wavetrace
