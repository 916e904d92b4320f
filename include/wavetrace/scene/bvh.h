// Flattened bounding volume hierarchy over all of a scene's primitives (triangles, quads,
// spheres), built with the binned surface-area heuristic.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "wavetrace/math/aabb.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct Scene;

// 32 bytes, two per cache line. Nodes are stored depth-first: an interior node's first child
// is the next node and `offset` indexes its second child; a leaf's primitives are
// prims()[offset, offset + count).
struct BvhNode {
    Vec3 lo;
    uint32_t offset;
    Vec3 hi;
    uint32_t count;  // 0 for interior nodes

    bool is_leaf() const { return count != 0; }
    Aabb bounds() const { return {lo, hi}; }
};
static_assert(sizeof(BvhNode) == 32);

// A primitive's geometry copied into leaf order, so that a leaf's primitives are read from one
// contiguous block without indirection. Triangle: a, b, c are the vertices. Quad: a = q,
// b = u, c = v. Sphere: a = centre, b.x = radius.
struct BvhPrim {
    Vec3 a, b, c;
    PrimRef ref;
};
static_assert(sizeof(BvhPrim) == 40);

struct BvhBuildConfig {
    int bins = 32;                     // SAH bins per axis
    int max_leaf_size = 8;             // leaves never hold more primitives than this
    float traversal_cost = 1.0f;       // SAH cost of visiting a node ...
    float intersection_cost = 1.0f;    // ... relative to testing one primitive
    size_t parallel_threshold = 4096;  // subtrees larger than this are built in parallel
};

struct BvhStats {
    size_t nodes = 0;
    size_t leaves = 0;
    int depth = 0;  // of the deepest leaf, the root at depth 1
    float sah_cost =
        0;  // expected cost of a random ray hitting the root box, in the config's units
    double build_ms = 0;
    size_t bytes = 0;  // nodes, primitive references and leaf-ordered primitive data
};

// The closest hit found along a ray; prim is invalid for a miss.
struct Hit {
    float t = kInfinity;
    PrimRef prim;
    float u = 0, v = 0;  // see PrimHit

    bool found() const { return prim.valid(); }
};

class Bvh {
  public:
    Bvh() = default;
    // Builds over every primitive of `scene`, which must outlive the BVH and not change.
    // The result does not depend on the number of threads.
    static Bvh build(const Scene& scene, const BvhBuildConfig& config = {});

    // Closest hit in [ray.tmin, ray.tmax].
    Hit intersect(const Ray& ray) const;
    // Whether anything is hit in [ray.tmin, ray.tmax].
    bool occluded(const Ray& ray) const;

    std::span<const BvhNode> nodes() const { return nodes_; }
    std::span<const PrimRef> prims() const { return prims_; }  // in leaf order
    const BvhStats& stats() const { return stats_; }
    const Scene* scene() const { return scene_; }

    static constexpr int kStackSize = 64;  // the build caps the depth below this

  private:
    template <bool AnyHit>
    bool traverse(const Ray& ray, Hit* hit) const;

    const Scene* scene_ = nullptr;
    std::vector<BvhNode> nodes_;
    std::vector<PrimRef> prims_;
    std::vector<BvhPrim> prim_data_;  // prims_' geometry, same order
    BvhStats stats_;
};

}  // namespace wavetrace
