// Flattened bounding volume hierarchy over all of a scene's primitives (triangles, quads,
// spheres), built with the binned surface-area heuristic.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "wavetrace/math/aabb.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct Scene;
struct BvhLayout;

struct BvhBuildConfig {
    int bins = 32;                     // SAH bins per axis
    int max_leaf_size = 16;            // leaves never hold more primitives than this
    int block_width = 8;               // primitives tested at once: the SAH counts blocks
    float traversal_cost = 1.0f;       // SAH cost of visiting a wide node (a binary node
                                       // costs a quarter: bvh_build.cpp) ...
    float intersection_cost = 1.0f;    // ... relative to testing one block of primitives
    size_t parallel_threshold = 4096;  // subtrees larger than this are built in parallel
};

struct BvhStats {
    size_t nodes = 0;
    size_t leaves = 0;
    int depth = 0;  // of the deepest leaf, the root at depth 1
    float sah_cost =
        0;  // expected cost of a random ray hitting the root box, in the config's units
    double build_ms = 0;    // binary build and collapse
    size_t bytes = 0;       // binary nodes and primitive references
    size_t wide_nodes = 0;  // nodes of the traversal layout
    size_t wide_bytes = 0;  // its nodes and leaf blocks
};

// The closest hit found along a ray; prim is invalid for a miss.
struct Hit {
    float t = kInfinity;
    PrimRef prim;
    float u = 0, v = 0;  // see PrimHit

    bool found() const { return prim.valid(); }
};

// A binned-SAH binary tree, collapsed into an 8-wide layout that rays walk with SIMD box and
// primitive tests on whatever the CPU has (see docs/architecture.md).
class Bvh {
  public:
    Bvh();
    ~Bvh();
    Bvh(Bvh&&) noexcept;
    Bvh& operator=(Bvh&&) noexcept;
    // Builds over every primitive of `scene`, which must outlive the BVH and not change.
    // The result does not depend on the number of threads.
    static Bvh build(const Scene& scene, const BvhBuildConfig& config = {});

    // Closest hit in [ray.tmin, ray.tmax].
    Hit intersect(const Ray& ray) const;
    // Whether anything is hit in [ray.tmin, ray.tmax].
    bool occluded(const Ray& ray) const;
    // The hit that the occlusion test stops at: one in [ray.tmin, ray.tmax], the first found,
    // not necessarily the closest (none if nothing is hit). Says what blocks a shadow ray.
    Hit any_hit(const Ray& ray) const;
    // The same for rays.size() rays, traversed as packets of up to 8 rays: faster for coherent
    // rays (a pixel tile's camera rays, its shadow rays towards one light), the same results.
    void intersect_packet(std::span<const Ray> rays, std::span<Hit> hits) const;
    void occluded_packet(std::span<const Ray> rays, std::span<bool> occluded) const;
    // intersect / occluded of each of rays.size() rays (incoherent: no packets), in one call:
    // a stream of rays pays for the choice of SIMD target once, not once per ray.
    void intersect_each(std::span<const Ray> rays, std::span<Hit> hits) const;
    void occluded_each(std::span<const Ray> rays, std::span<bool> occluded) const;
    void any_hit_each(std::span<const Ray> rays, std::span<Hit> hits) const;

    const BvhStats& stats() const { return stats_; }
    // The trees themselves, for the library's own checks; the type is internal.
    const BvhLayout& layout() const { return *layout_; }
    const Scene* scene() const { return scene_; }

    static constexpr int kStackSize = 64;  // the build caps the depth below this

  private:
    const Scene* scene_ = nullptr;
    std::unique_ptr<BvhLayout> layout_;
    BvhStats stats_;
};

// The SIMD target the traversal runs on this CPU (Highway's name, e.g. "AVX2", "AVX3").
const char* simd_target();

// The SIMD targets compiled in that this CPU runs (Highway's names), the best first.
std::vector<std::string> simd_targets();

// Runs every kernel (traversal, shading, sampling) on the named target of simd_targets() from
// now on, e.g. "AVX2" to measure what a CPU without AVX-512 gets; "" returns to the best.
// False, and nothing changed, for a target not among them.
bool use_simd_target(const std::string& name);

}  // namespace wavetrace
