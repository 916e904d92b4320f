// Groups a wave's entries by material kind so that shading runs over contiguous, same-kind
// ranges: coherent branches, and (later) SIMD over a range.
#include "kernels/kernels.h"

namespace wavetrace {

int sort_key(const Scene& scene, PrimRef prim) {
    return prim.valid() ? 1 + static_cast<int>(scene.materials[scene.prim_material(prim)].kind) : 0;
}

KeyRanges sort_by_material(const Scene& scene,
                           size_t begin,
                           size_t end,
                           std::span<uint8_t> key,
                           PathQueue& paths,
                           RayQueue& rays,
                           HitQueue& hits) {
    KeyRanges start{};
    start[0] = static_cast<uint32_t>(begin);
    for (size_t i = begin; i < end; ++i) {
        key[i] = static_cast<uint8_t>(sort_key(scene, hits.prim[i]));
        ++start[key[i] + 1];
    }
    for (int k = 0; k < kSortKeys; ++k) start[k + 1] += start[k];
    // Each bucket's next unfilled slot; an entry found in the wrong bucket is swapped into its
    // own, so every entry moves at most once.
    KeyRanges next = start;
    for (int k = 0; k < kSortKeys; ++k) {
        while (next[k] < start[k + 1]) {
            const size_t i = next[k];
            const int home = key[i];
            if (home == k) {
                ++next[k];
                continue;
            }
            const size_t j = next[home]++;
            std::swap(key[i], key[j]);
            paths.swap(i, j);
            rays.swap(i, j);
            hits.swap(i, j);
        }
    }
    return start;
}

}  // namespace wavetrace
