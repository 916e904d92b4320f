// Groups hits by material kind so that each shading run covers a contiguous, same-kind range
// (coherent branches and memory access), by a counting sort: stable, so deterministic.
#include <array>

#include "kernels/kernels.h"

namespace wavetrace {

namespace {
constexpr int kKinds = 8;  // miss + the MaterialKind values
}

void bucket_by_material(const WaveInputs& in, WaveQueues& q, size_t n) {
    std::vector<uint32_t>& key = q.bucket_scratch;
    std::array<uint32_t, kKinds + 1> start{};
    for (size_t i = 0; i < n; ++i) {
        PrimRef prim = q.hits.prim[i];
        key[i] =
            prim.valid()
                ? 1 + static_cast<uint32_t>(in.scene.materials[in.scene.prim_material(prim)].kind)
                : 0;
        ++start[key[i] + 1];
    }
    for (int k = 0; k < kKinds; ++k) start[k + 1] += start[k];
    for (size_t i = 0; i < n; ++i) q.order[start[key[i]]++] = static_cast<uint32_t>(i);
}

}  // namespace wavetrace
