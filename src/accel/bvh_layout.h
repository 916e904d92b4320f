// What a Bvh holds: the binary tree it was built as and the wide layout rays walk.
#pragma once

#include <vector>

#include "accel/binary_bvh.h"
#include "accel/wide_bvh.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

struct BvhLayout {
    std::vector<BvhNode> nodes;  // depth-first, the root first
    std::vector<PrimRef> prims;  // in leaf order
    WideBvh wide;
};

}  // namespace wavetrace
