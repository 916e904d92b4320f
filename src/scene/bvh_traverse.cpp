#include <algorithm>
#include <cmath>

#include "wavetrace/scene/bvh.h"
#include "wavetrace/scene/intersect.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

inline bool intersect_prim(const Scene& scene, PrimRef ref, const Ray& ray, PrimHit* hit) {
    uint32_t i = ref.index();
    switch (ref.kind()) {
        case PrimKind::Triangle: {
            const Triangle& tri = scene.triangles[i];
            return intersect_triangle(ray, scene.positions[tri.v[0]], scene.positions[tri.v[1]],
                                      scene.positions[tri.v[2]], hit);
        }
        case PrimKind::Quad: {
            const Quad& q = scene.quads[i];
            return intersect_quad(ray, q.q, q.u, q.v, hit);
        }
        case PrimKind::Sphere: {
            const Sphere& s = scene.spheres[i];
            return intersect_sphere(ray, s.center, s.radius, hit);
        }
    }
    return false;
}

// Slab test. fmin/fmax drop the NaN of 0 * inf (a ray in a slab's boundary plane), and the
// exit distance is widened by 1 + 2 gamma(3) so that rounding never culls a box the ray
// really touches (Ize, "Robust BVH Ray Traversal", JCGT 2(2), 2013).
inline bool hit_box(const BvhNode& node, Vec3 o, Vec3 inv_d, float tmin, float tmax,
                    float* t_entry) {
    float tx0 = (node.lo.x - o.x) * inv_d.x, tx1 = (node.hi.x - o.x) * inv_d.x;
    float ty0 = (node.lo.y - o.y) * inv_d.y, ty1 = (node.hi.y - o.y) * inv_d.y;
    float tz0 = (node.lo.z - o.z) * inv_d.z, tz1 = (node.hi.z - o.z) * inv_d.z;
    float t_near = std::fmax(std::fmax(std::fmin(tx0, tx1), std::fmin(ty0, ty1)),
                             std::fmax(std::fmin(tz0, tz1), tmin));
    float t_far = std::fmin(std::fmin(std::fmax(tx0, tx1), std::fmax(ty0, ty1)),
                            std::fmax(tz0, tz1)) *
                  (1.0f + 2.0f * gamma(3));
    *t_entry = t_near;
    return t_near <= std::fmin(t_far, tmax);
}

}  // namespace

template <bool AnyHit>
bool Bvh::traverse(const Ray& ray_in, Hit* hit) const {
    if (nodes_.empty()) return false;
    Ray ray = ray_in;
    const Vec3 inv_d{1.0f / ray.d.x, 1.0f / ray.d.y, 1.0f / ray.d.z};
    const Scene& scene = *scene_;

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
                if (intersect_prim(scene, prims_[i], ray, &ph)) {
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
                if (tb < ta) {
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
