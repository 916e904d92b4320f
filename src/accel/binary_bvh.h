// The binary SAH tree, flattened: the source of truth the wide traversal layout is collapsed
// from (bvh_build.cpp builds it).
#pragma once

#include <cstdint>

#include "wavetrace/math/aabb.h"

namespace wavetrace {

// 32 bytes, two per cache line. Nodes are stored depth-first: an interior node's first child
// is the next node and `offset` indexes its second child; a leaf's primitives are
// BvhLayout::prims[offset, offset + count).
struct BvhNode {
    Vec3 lo;
    uint32_t offset;
    Vec3 hi;
    uint32_t count;  // 0 for interior nodes

    bool is_leaf() const { return count != 0; }
    Aabb bounds() const { return {lo, hi}; }
};
static_assert(sizeof(BvhNode) == 32);

}  // namespace wavetrace
