#include "accel/intersect.h"

#include <cmath>

#include "accel/sphere_hit-inl.h"
#include "wavetrace/math/constants.h"

namespace wavetrace {
namespace lanes = HWY_NAMESPACE;
using lanes::OneLane, lanes::to_lanes;

bool intersect_sphere(const Ray& ray, Point3 center, float radius, PrimHit* hit) {
    float t;
    if (!lanes::SphereHit<OneLane>(to_lanes(ray.o), to_lanes(ray.d), to_lanes(center), radius,
                                   ray.tmin, ray.tmax, &t))
        return false;
    *hit = {t, 0.0f, 0.0f};
    return true;
}

bool intersect_quad(const Ray& ray, Point3 q, Vec3 u, Vec3 v, PrimHit* hit) {
    Vec3 n = cross(u, v);
    float denom = dot(n, ray.d);
    if (denom == 0.0f) return false;  // parallel to the plane
    float t = dot(n, q - ray.o) / denom;
    if (!(t >= ray.tmin && t <= ray.tmax)) return false;
    // Planar coordinates of the hit: p - q = alpha u + beta v, solved with w = n / (n.n).
    Vec3 p = ray.at(t) - q;
    Vec3 w = n / dot(n, n);
    float alpha = dot(w, cross(p, v));
    float beta = dot(w, cross(u, p));
    if (!(alpha >= 0.0f && alpha <= 1.0f && beta >= 0.0f && beta <= 1.0f)) return false;
    *hit = {t, alpha, beta};
    return true;
}

namespace {

inline Vec3 permute(Vec3 v, int x, int y, int z) {
    return {v[x], v[y], v[z]};
}

}  // namespace

bool intersect_triangle(const Ray& ray, Point3 p0, Point3 p1, Point3 p2, PrimHit* hit) {
    return intersect_triangle(TriangleRay(ray), ray.tmin, ray.tmax, p0, p1, p2, hit);
}

bool intersect_triangle(
    const TriangleRay& r, float tmin, float tmax, Point3 p0, Point3 p1, Point3 p2, PrimHit* hit) {
    // Translate to the ray origin, permute so that the ray's largest direction component is z,
    // then shear so that the ray runs along +z: the test becomes a 2-D edge-function test at
    // the origin, evaluated identically for the two triangles sharing an edge.
    const int kx = r.kx, ky = r.ky, kz = r.kz;
    const float sx = r.sx, sy = r.sy, sz = r.sz;
    Vec3 p0t = permute(p0 - r.o, kx, ky, kz);
    Vec3 p1t = permute(p1 - r.o, kx, ky, kz);
    Vec3 p2t = permute(p2 - r.o, kx, ky, kz);
    p0t.x += sx * p0t.z;
    p0t.y += sy * p0t.z;
    p1t.x += sx * p1t.z;
    p1t.y += sy * p1t.z;
    p2t.x += sx * p2t.z;
    p2t.y += sy * p2t.z;

    // 2-D edge functions. In float, the triangle on the other side of a shared edge computes
    // exactly the negation of this one's value for that edge (same products, subtraction
    // reversed; no FMA contraction under -std=c++20), so the two never both miss a ray through
    // it. Only a result of exactly 0 is ambiguous; it is recomputed in double, where the
    // products of floats are exact (Woop et al. §3.3).
    float e0 = p1t.x * p2t.y - p1t.y * p2t.x;
    float e1 = p2t.x * p0t.y - p2t.y * p0t.x;
    float e2 = p0t.x * p1t.y - p0t.y * p1t.x;
    if (e0 == 0.0f || e1 == 0.0f || e2 == 0.0f) {
        e0 = static_cast<float>(double(p1t.x) * p2t.y - double(p1t.y) * p2t.x);
        e1 = static_cast<float>(double(p2t.x) * p0t.y - double(p2t.y) * p0t.x);
        e2 = static_cast<float>(double(p0t.x) * p1t.y - double(p0t.y) * p1t.x);
    }
    if ((e0 < 0 || e1 < 0 || e2 < 0) && (e0 > 0 || e1 > 0 || e2 > 0)) return false;
    float det = e0 + e1 + e2;
    if (det == 0.0f) return false;

    p0t.z *= sz;
    p1t.z *= sz;
    p2t.z *= sz;
    float t_scaled = e0 * p0t.z + e1 * p1t.z + e2 * p2t.z;
    if (det < 0 && (t_scaled > tmin * det || t_scaled < tmax * det)) return false;
    if (det > 0 && (t_scaled < tmin * det || t_scaled > tmax * det)) return false;

    float inv_det = 1.0f / det;
    float t = t_scaled * inv_det;

    // Reject hits whose t may be <= 0 given the rounding error of the computation above
    // (pbrt-v4, §6.8.7): keeps a ray leaving a triangle from hitting it again.
    float max_zt = max_component(abs(Vec3{p0t.z, p1t.z, p2t.z}));
    float delta_z = gamma(3) * max_zt;
    float max_xt = max_component(abs(Vec3{p0t.x, p1t.x, p2t.x}));
    float max_yt = max_component(abs(Vec3{p0t.y, p1t.y, p2t.y}));
    float delta_x = gamma(5) * (max_xt + max_zt);
    float delta_y = gamma(5) * (max_yt + max_zt);
    float delta_e = 2 * (gamma(2) * max_xt * max_yt + delta_y * max_xt + delta_x * max_yt);
    float max_e = max_component(abs(Vec3{e0, e1, e2}));
    float delta_t =
        3 * (gamma(3) * max_e * max_zt + delta_e * max_zt + delta_z * max_e) * std::fabs(inv_det);
    if (t <= delta_t) return false;

    *hit = {t, e1 * inv_det, e2 * inv_det};
    return true;
}

}  // namespace wavetrace
