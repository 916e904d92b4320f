// One ray's walk of the wide BVH, per target: what the single-ray traversal
// (wide_bvh_traverse.cpp) does from the root, and the packet traversal (wide_bvh_packets.cpp)
// from the subtrees that too few of a packet's rays enter to be walked together.
#if defined(WAVETRACE_ACCEL_WIDE_RAY_WALK_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_ACCEL_WIDE_RAY_WALK_INL_H_
#undef WAVETRACE_ACCEL_WIDE_RAY_WALK_INL_H_
#else
#define WAVETRACE_ACCEL_WIDE_RAY_WALK_INL_H_
#endif

#include <hwy/highway.h>

#include "accel/wide_bvh.h"
#include "accel/wide_leaf_tests-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// One ray's walk of the subtree `root` (a node or a leaf's child code; 0: the whole tree) for
// both queries: the nearest hit within [tmin, *tmax] into *hit and *tmax lowered to its t, or
// for AnyHit the first found; returns whether one was. Children are visited nearest entry first;
// the others wait on the stack with their entry distance and are skipped once a closer hit is
// known.
template <bool AnyHit>
HWY_INLINE bool WalkSubtree(
    const WideBvh& bvh, const RayLanes& r, uint32_t root, float* tmax_io, Hit* hit) {
    const Ray& ray = r.ray;
    float tmax = *tmax_io;
    bool found = false;

    struct Entry {
        uint32_t code;
        float t_entry;
    };
    // Each level pushes at most kWideNodeWidth - 1 entries, and the depth is below
    // Bvh::kStackSize.
    Entry stack[Bvh::kStackSize * (kWideNodeWidth - 1) + 1];
    int sp = 0;
    uint32_t code = root;
    HWY_ALIGN float t_entry[kWideNodeWidth];
    BlockHits hits;

    for (;;) {
        if (!(code & kLeafChild)) {
            const WideNode& node = bvh.nodes[code];
            uint32_t bits = BoxTest(node, r, tmax, t_entry);
            if (bits != 0) {
                // Push the hit children farthest first, so that the nearest is taken now and
                // the next nearest is on top of the stack.
                uint32_t first = static_cast<uint32_t>(__builtin_ctz(bits));
                bits &= bits - 1;
                if (bits == 0) {
                    code = node.child[first];
                    continue;
                }
                int base = sp;
                stack[sp++] = {node.child[first], t_entry[first]};
                while (bits != 0) {
                    uint32_t c = static_cast<uint32_t>(__builtin_ctz(bits));
                    bits &= bits - 1;
                    Entry e{node.child[c], t_entry[c]};
                    int j = sp++;
                    if (!AnyHit)  // insertion sort: descending entry distance
                        for (; j > base && stack[j - 1].t_entry < e.t_entry; --j)
                            stack[j] = stack[j - 1];
                    stack[j] = e;
                }
                code = stack[--sp].code;
                continue;
            }
        } else {
            // Blocks of one kind straight from the child code (all lanes: unused ones repeat
            // lane 0), or through leaf_blocks for a leaf of several kinds.
            const uint32_t kind = leaf_kind(code), first = leaf_first(code);
            const uint32_t count = leaf_block_count(code);
            for (uint32_t k = first; k < first + count; ++k) {
                const LeafBlock lb = kind == kMixedLeaf ? bvh.leaf_blocks[k]
                                                        : LeafBlock{static_cast<PrimKind>(kind),
                                                                    uint32_t(kLeafBlockWidth), k};
                const PrimRef* refs = nullptr;
                hits.bits = 0;
                switch (lb.kind) {
                    case PrimKind::Triangle:
                        TriangleTest(bvh.triangles[lb.index], lb.count, r, tmax, &hits);
                        refs = bvh.triangles[lb.index].ref;
                        break;
                    case PrimKind::Quad:
                        QuadTest(bvh.quads[lb.index], lb.count, r, tmax, &hits);
                        refs = bvh.quads[lb.index].ref;
                        break;
                    case PrimKind::Sphere:
                        SphereTest(bvh.spheres[lb.index], lb.count, r, tmax, &hits);
                        refs = bvh.spheres[lb.index].ref;
                        break;
                }
                if (bvh.masks != nullptr && hits.bits != 0)
                    hits.bits = uncut_hits(bvh, hits.bits, refs, hits.t, hits.u, hits.v, ray, tmax);
                if (hits.bits == 0) continue;
                if constexpr (AnyHit) {  // the first lane that hits: which one blocks the ray
                    const uint32_t l = static_cast<uint32_t>(__builtin_ctz(hits.bits));
                    *hit = {hits.t[l], refs[l], hits.u[l], hits.v[l]};
                    *tmax_io = hits.t[l];
                    return true;
                }
                // The nearest lane; lanes are tested in order and a later one at equal t
                // wins, as in a scalar loop with an inclusive tmax (a repeat of lane 0 gives
                // lane 0's hit again).
                for (uint32_t bits = hits.bits; bits != 0; bits &= bits - 1) {
                    uint32_t l = static_cast<uint32_t>(__builtin_ctz(bits));
                    if (hits.t[l] <= tmax) {
                        tmax = hits.t[l];
                        *hit = {hits.t[l], refs[l], hits.u[l], hits.v[l]};
                        found = true;
                    }
                }
            }
        }
        // Pop the next subtree that may still hold a closer hit.
        for (;;) {
            if (sp == 0) {
                *tmax_io = tmax;
                return found;
            }
            const Entry e = stack[--sp];
            if (e.t_entry <= tmax) {
                code = e.code;
                break;
            }
        }
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_ACCEL_WIDE_RAY_WALK_INL_H_
