#include "scene/hit_geometry.h"

#include <cmath>

#include "wavetrace/math/constants.h"
#include "wavetrace/scene/scene.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

Vec2 hit_uv(const Scene& scene, PrimRef prim, float u, float v, Point3 p) {
    switch (prim.kind()) {
        case PrimKind::Triangle: {
            const Triangle& tri = scene.triangles[prim.index()];
            if (!scene.meshes[tri.mesh].has_uvs) return {u, v};
            const Vec2 t0 = scene.uvs[tri.v[0]], t1 = scene.uvs[tri.v[1]], t2 = scene.uvs[tri.v[2]];
            const float w = 1.0f - u - v;
            return {w * t0.x + u * t1.x + v * t2.x, w * t0.y + u * t1.y + v * t2.y};
        }
        case PrimKind::Quad:
            return {u, scene.quads[prim.index()].flip_v ? 1.0f - v : v};
        case PrimKind::Sphere: {
            const Sphere& s = scene.spheres[prim.index()];
            return sphere_uv(scene, s, (p - s.center) / s.radius);
        }
    }
    return {};
}

Tangents hit_tangents(const Scene& scene, PrimRef prim, Point3 p) {
    Tangents t;
    switch (prim.kind()) {
        case PrimKind::Triangle: {
            const Triangle& tri = scene.triangles[prim.index()];
            const Point3 p0 = scene.positions[tri.v[0]];
            const Vec3 e1 = scene.positions[tri.v[1]] - p0, e2 = scene.positions[tri.v[2]] - p0;
            t.dpdu = e1;
            t.dpdv = e2;
            if (!scene.meshes[tri.mesh].has_uvs) return t;
            // [e1 e2] = [dpdu dpdv] [[du1 du2] [dv1 dv2]]: invert the 2 x 2 uv matrix.
            const Vec2 t0 = scene.uvs[tri.v[0]], t1 = scene.uvs[tri.v[1]], t2 = scene.uvs[tri.v[2]];
            const Vec2 d1{t1.x - t0.x, t1.y - t0.y}, d2{t2.x - t0.x, t2.y - t0.y};
            const float det = d1.x * d2.y - d1.y * d2.x;
            if (!(std::fabs(det) > 1e-12f)) return t;
            const float inv = 1.0f / det;
            t.dpdu = (d2.y * e1 - d1.y * e2) * inv;
            t.dpdv = (d1.x * e2 - d2.x * e1) * inv;
            return t;
        }
        case PrimKind::Quad: {
            const Quad& q = scene.quads[prim.index()];
            t.dpdu = q.u;
            t.dpdv = q.flip_v ? -q.v : q.v;
            return t;
        }
        case PrimKind::Sphere: {
            // In the sphere's own frame, p = c + r n:
            // YUp: n = (-sin theta cos phi, -cos theta, sin theta sin phi) at
            //      (u, v) = (phi / 2 pi, theta / pi);
            // ZUp: n = (sin theta cos phi, sin theta sin phi, cos theta) at
            //      (u, v) = (phi / 2 pi, 1 - theta / pi).
            const Sphere& s = scene.spheres[prim.index()];
            const Frame* frame = s.frame == kNone ? nullptr : &scene.sphere_frames[s.frame];
            Vec3 n = (p - s.center) / s.radius;
            if (frame) n = frame->to_local(n);
            const float r = s.radius;
            if (s.mapping == SphereMapping::YUp) {
                const float sin_theta = std::sqrt(std::fmax(0.0f, n.x * n.x + n.z * n.z));
                if (!(sin_theta > 1e-6f)) return t;  // a pole
                const float cos_phi = -n.x / sin_theta, sin_phi = n.z / sin_theta, cos_theta = -n.y;
                t.dpdu = 2.0f * kPi * r * Vec3{sin_theta * sin_phi, 0.0f, sin_theta * cos_phi};
                t.dpdv = kPi * r * Vec3{-cos_theta * cos_phi, sin_theta, cos_theta * sin_phi};
            } else {
                const float sin_theta = std::sqrt(std::fmax(0.0f, n.x * n.x + n.y * n.y));
                if (!(sin_theta > 1e-6f)) return t;  // a pole
                const float cos_phi = n.x / sin_theta, sin_phi = n.y / sin_theta, cos_theta = n.z;
                t.dpdu = 2.0f * kPi * r * Vec3{-n.y, n.x, 0.0f};
                t.dpdv = kPi * r * Vec3{-cos_theta * cos_phi, -cos_theta * sin_phi, sin_theta};
            }
            if (frame) {
                t.dpdu = frame->to_world(t.dpdu);
                t.dpdv = frame->to_world(t.dpdv);
            }
            return t;
        }
    }
    return t;
}

}  // namespace wavetrace
