#include <algorithm>
#include <cmath>

#include "wavetrace/scene/bvh.h"
#include "wavetrace/scene/intersect.h"

namespace wavetrace {
namespace {

inline bool intersect_prim(const BvhPrim& p,
                           const Ray& ray,
                           const TriangleRay& tri_ray,
                           PrimHit* hit) {
    switch (p.ref.kind()) {
        case PrimKind::Triangle:
            return intersect_triangle(tri_ray, ray.tmin, ray.tmax, p.a, p.b, p.c, hit);
        case PrimKind::Quad:
            return intersect_quad(ray, p.a, p.b, p.c, hit);
        case PrimKind::Sphere:
            return intersect_sphere(ray, p.a, p.b.x, hit);
    }
    return false;
}

// Branch-free min/max that compile to minss/maxss (std::fmin is a libm call without
// -ffast-math). Inputs are never NaN: see safe_inverse().
inline float min2(float a, float b) {
    return a < b ? a : b;
}
inline float max2(float a, float b) {
    return a > b ? a : b;
}

// 1/d with zero components replaced by a huge finite value of the same sign: the slab
// distances (lo - o) / d then stay finite (a ray inside a slab's boundary plane gives 0, not
// the NaN of 0 * inf), so the slab test needs no NaN handling.
inline float safe_inverse(float d) {
    return std::fabs(d) > 1e-30f ? 1.0f / d : std::copysign(1e30f, d);
}

// Slab test; the exit distance is widened by 1 + 2 gamma(3) so that rounding never culls a
// box the ray really touches (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013).
inline bool hit_box(
    const BvhNode& node, Vec3 o, Vec3 inv_d, float tmin, float tmax, float* t_entry) {
    float tx0 = (node.lo.x - o.x) * inv_d.x, tx1 = (node.hi.x - o.x) * inv_d.x;
    float ty0 = (node.lo.y - o.y) * inv_d.y, ty1 = (node.hi.y - o.y) * inv_d.y;
    float tz0 = (node.lo.z - o.z) * inv_d.z, tz1 = (node.hi.z - o.z) * inv_d.z;
    float t_near = max2(max2(min2(tx0, tx1), min2(ty0, ty1)), max2(min2(tz0, tz1), tmin));
    float t_far =
        min2(min2(max2(tx0, tx1), max2(ty0, ty1)), max2(tz0, tz1)) * (1.0f + 2.0f * gamma(3));
    *t_entry = t_near;
    return t_near <= min2(t_far, tmax);
}

}  // namespace

template <bool AnyHit>
bool Bvh::traverse(const Ray& ray_in, Hit* hit) const {
    if (nodes_.empty()) return false;
    Ray ray = ray_in;
    const Vec3 inv_d{safe_inverse(ray.d.x), safe_inverse(ray.d.y), safe_inverse(ray.d.z)};
    const TriangleRay tri_ray(ray);

    struct Entry {
        uint32_t node;
        float t_entry;
    };
    Entry stack[kStackSize];
    int sp = 0;
    float t_root;
    if (!hit_box(nodes_[0], ray.o, inv_d, ray.tmin, ray.tmax, &t_root)) return false;

    bool found = false;
    uint32_t current = 0;
    for (;;) {
        const BvhNode& node = nodes_[current];
        if (node.is_leaf()) {
            for (uint32_t i = node.offset; i < node.offset + node.count; ++i) {
                PrimHit ph;
                if (intersect_prim(prim_data_[i], ray, tri_ray, &ph)) {
                    found = true;
                    if constexpr (AnyHit) return true;
                    ray.tmax = ph.t;
                    *hit = {ph.t, prims_[i], ph.u, ph.v};
                }
            }
        } else {
            // Visit the nearer child first; the farther one waits on the stack with its entry
            // distance so that it is skipped if a closer hit turns up meanwhile.
            uint32_t a = current + 1, b = node.offset;
            float ta, tb;
            bool hit_a = hit_box(nodes_[a], ray.o, inv_d, ray.tmin, ray.tmax, &ta);
            bool hit_b = hit_box(nodes_[b], ray.o, inv_d, ray.tmin, ray.tmax, &tb);
            if (hit_a && hit_b) {
                // Any-hit traversal takes any order: only closest-hit gains from near-first.
                if (!AnyHit && tb < ta) {
                    std::swap(a, b);
                    std::swap(ta, tb);
                }
                stack[sp++] = {b, tb};
                current = a;
                continue;
            }
            if (hit_a || hit_b) {
                current = hit_a ? a : b;
                continue;
            }
        }
        // Pop the next subtree that may still hold a closer hit.
        for (;;) {
            if (sp == 0) return found;
            Entry e = stack[--sp];
            if (e.t_entry <= ray.tmax) {
                current = e.node;
                break;
            }
        }
    }
}

Hit Bvh::intersect(const Ray& ray) const {
    Hit hit;
    traverse<false>(ray, &hit);
    return hit;
}

bool Bvh::occluded(const Ray& ray) const {
    Hit unused;
    return traverse<true>(ray, &unused);
}

}  // namespace wavetrace
