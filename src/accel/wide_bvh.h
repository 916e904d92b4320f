// The traversal layout of the BVH: the binary SAH tree collapsed into nodes of kWideNodeWidth
// children whose boxes are stored as SoA float lanes, and leaves whose primitives are gathered
// into blocks of kLeafBlockWidth primitives of one kind, tested all at once. The binary tree
// stays the source of truth (bvh_build.cpp); this is what rays walk (wide_bvh_traverse.cpp,
// wide_bvh_packets.cpp). The layout follows Embree's BVH8 (Wald et al., "Embree: A Kernel Framework
// for Efficient CPU Ray Tracing", SIGGRAPH 2014) and Wald, Benthin and Boulos, "Getting Rid of
// Packets" (2008).
#pragma once

#include <cstdint>
#include <vector>

#include "accel/binary_bvh.h"
#include "scene/opacity.h"
#include "util/huge_pages.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/math/ray.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {

// 8 wide beat 4 wide on nodes and on blocks (docs/benchmarks.md, "Wide BVH"): on AVX2 and
// AVX-512 an 8-lane test costs what a 4-lane one does, and halves the depth.
inline constexpr int kWideNodeWidth = 8;
inline constexpr int kLeafBlockWidth = 8;

// Child codes: a node index, kEmptyChild for an unused slot, or a leaf: kLeafChild | kind <<
// kLeafKindShift | block count << kLeafCountShift | first block. A leaf whose primitives are of
// one kind (nearly all of them) names that kind, and its blocks lie at [first, first + count)
// of that kind's block array, so a ray goes from the child code straight to the blocks; a leaf
// of several kinds is kMixedLeaf, and its blocks are leaf_blocks[first, first + count).
inline constexpr uint32_t kLeafChild = 0x80000000u;
inline constexpr int kLeafKindShift = 29;
inline constexpr uint32_t kMixedLeaf = 3;
inline constexpr int kLeafCountShift = 25;
inline constexpr uint32_t kLeafFirstMask = (1u << kLeafCountShift) - 1;
inline constexpr uint32_t kMaxLeafBlocks = 15;
inline constexpr uint32_t kEmptyChild = 0xffffffffu;

inline uint32_t leaf_kind(uint32_t code) {
    return (code >> kLeafKindShift) & 3u;
}
inline uint32_t leaf_block_count(uint32_t code) {
    return (code >> kLeafCountShift) & kMaxLeafBlocks;
}
inline uint32_t leaf_first(uint32_t code) {
    return code & kLeafFirstMask;
}

// An empty slot's box is inverted (lo = +inf, hi = -inf): its entry distance is +inf for every
// ray, so the box test culls it without a separate check.
struct alignas(64) WideNode {
    float bounds[6][kWideNodeWidth];  // lo_x, hi_x, lo_y, hi_y, lo_z, hi_z of each child
    uint32_t child[kWideNodeWidth];
};
static_assert(sizeof(WideNode) == 256);

// Unused lanes of a block repeat lane 0, primitive and reference: every lane holds ordinary
// numbers, and testing all lanes finds nothing lane 0 does not (a ray needs no lane count).
struct alignas(32) TriangleBlock {
    float p[3][3][kLeafBlockWidth];  // vertex, axis, lane
    PrimRef ref[kLeafBlockWidth];
};
// q, u, v as in the scene; n = cross(u, v) and w = n / dot(n, n) precomputed, with the same
// float operations intersect_quad() performs, so the block test gives the same bits.
struct alignas(32) QuadBlock {
    float q[3][kLeafBlockWidth], u[3][kLeafBlockWidth], v[3][kLeafBlockWidth];
    float n[3][kLeafBlockWidth], w[3][kLeafBlockWidth];
    PrimRef ref[kLeafBlockWidth];
};
struct alignas(32) SphereBlock {
    float c[3][kLeafBlockWidth], r[kLeafBlockWidth];
    PrimRef ref[kLeafBlockWidth];
};

struct LeafBlock {
    PrimKind kind;
    uint32_t count;  // 1..kLeafBlockWidth
    uint32_t index;  // into the kind's block array
};

struct WideBvh {
    // The scene when any of its materials has an alpha mask: traversals then drop the hits that
    // cut_away (scene/opacity.h) cuts away. Null otherwise, and the hits are taken unseen.
    const Scene* masks = nullptr;
    // What rays walk, in huge pages where the system lends them (util/huge_pages.h).
    template <class T>
    using Array = std::vector<T, HugePageAllocator<T>>;
    Array<WideNode> nodes;         // nodes[0] is the root
    Array<LeafBlock> leaf_blocks;  // of the leaves of several kinds
    Array<TriangleBlock> triangles;
    Array<QuadBlock> quads;
    Array<SphereBlock> spheres;

    size_t bytes() const {
        return nodes.size() * sizeof(WideNode) + leaf_blocks.size() * sizeof(LeafBlock) +
               triangles.size() * sizeof(TriangleBlock) + quads.size() * sizeof(QuadBlock) +
               spheres.size() * sizeof(SphereBlock);
    }
};

// Whether the hit of `ray` on ref at *t (parameters u, v) survives the alpha masks. A sphere cut
// away where the ray enters it is met again where the ray leaves it (*t moves there) when that
// is within tmax and not cut away too, as Embree's filter functions see both.
inline bool uncut_hit(
    const WideBvh& bvh, PrimRef ref, float* t, float u, float v, const Ray& ray, float tmax) {
    if (!cut_away(*bvh.masks, ref, *t, u, v, ray)) return true;
    if (ref.kind() != PrimKind::Sphere) return false;
    // The two roots of |o + t d - c| = r sum to 2 d.(c - o) / d.d.
    const Sphere& s = bvh.masks->spheres[ref.index()];
    const float t_far = 2.0f * dot(ray.d, s.center - ray.o) / dot(ray.d, ray.d) - *t;
    if (!(t_far > *t && t_far <= tmax) || cut_away(*bvh.masks, ref, t_far, u, v, ray)) return false;
    *t = t_far;
    return true;
}

// Of the block's hits `bits` (lanes with their primitives refs[l] at t[l], u[l], v[l]) of
// `ray`, those that no alpha mask cuts away (uncut_hit; t[l] may move to a sphere's far side).
inline uint32_t uncut_hits(const WideBvh& bvh,
                           uint32_t bits,
                           const PrimRef* refs,
                           float* t,
                           const float* u,
                           const float* v,
                           const Ray& ray,
                           float tmax) {
    for (uint32_t b = bits; b != 0; b &= b - 1) {
        const uint32_t l = static_cast<uint32_t>(__builtin_ctz(b));
        if (!uncut_hit(bvh, refs[l], &t[l], u[l], v[l], ray, tmax)) bits &= ~(1u << l);
    }
    return bits;
}

// Block j of the leaf with child code `code`: its kind, the lanes in use and its index in the
// kind's block array.
inline LeafBlock leaf_block(const WideBvh& bvh, uint32_t code, uint32_t j) {
    const uint32_t kind = leaf_kind(code), index = leaf_first(code) + j;
    if (kind == kMixedLeaf) return bvh.leaf_blocks[index];
    const PrimRef* refs = kind == uint32_t(PrimKind::Triangle) ? bvh.triangles[index].ref
                          : kind == uint32_t(PrimKind::Quad)   ? bvh.quads[index].ref
                                                               : bvh.spheres[index].ref;
    uint32_t used = 1;  // lanes in use: up to the first repeat of lane 0
    while (used < uint32_t(kLeafBlockWidth) && refs[used] != refs[0]) ++used;
    return {static_cast<PrimKind>(kind), used, index};
}

// The SAH costs the collapse weighs (BvhBuildConfig's), and the most primitives a leaf of the
// wide tree may hold.
struct WideCollapseCosts {
    float traversal = 1.0f;
    float intersection = 1.0f;
    uint32_t max_leaf_size = 16;
};

// Collapses a built binary tree (nodes in depth-first order, leaves indexing `prims`).
WideBvh collapse_to_wide(const Scene& scene,
                         std::span<const BvhNode> nodes,
                         std::span<const PrimRef> prims,
                         const WideCollapseCosts& costs);

// Closest hit in [ray.tmin, ray.tmax] / whether anything is hit there. One traversal serves
// both; it runs on the best SIMD target this CPU supports (Highway's dynamic dispatch).
bool wide_intersect(const WideBvh& bvh, const Ray& ray, Hit* hit);
bool wide_occluded(const WideBvh& bvh, const Ray& ray);
// The first hit the occlusion test finds, in [ray.tmin, ray.tmax] (any one, not the closest).
bool wide_any_hit(const WideBvh& bvh, const Ray& ray, Hit* hit);
// The same for n rays, traversed as packets of up to 8 (a vector's worth of rays: 8 on AVX2 and
// AVX-512, 4 on SSE4 and NEON). For coherent rays, such as a pixel tile's camera rays or its
// shadow rays towards one light.
void wide_intersect_packet(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits);
void wide_occluded_packet(const WideBvh& bvh, const Ray* rays, size_t n, bool* occluded);
// wide_intersect / wide_occluded of n rays, one after the other, in one call.
void wide_intersect_each(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits);
void wide_occluded_each(const WideBvh& bvh, const Ray* rays, size_t n, bool* occluded);
void wide_any_hit_each(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits);
// The name of the SIMD target the traversal dispatches to on this CPU, e.g. "AVX2".
const char* wide_simd_target();
// For tests: the targets compiled in and supported by this CPU (Highway's HWY_* bits), and
// a way to run on one of them (0: back to the best).
std::vector<int64_t> wide_simd_targets();
void use_wide_simd_target(int64_t target);

}  // namespace wavetrace
