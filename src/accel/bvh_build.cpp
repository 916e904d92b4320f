// Binned SAH BVH build (Wald, "On fast Construction of SAH-based Bounding Volume
// Hierarchies", IRT 2007), flattened depth-first into 32-byte nodes.
#include <tbb/blocked_range.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>

#include "accel/bvh_layout.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

// A primitive's binning keys: its centroid on the three axes, and (key 3) log2 of its box's
// half area. The size key lets the SAH part large primitives from small ones where no plane
// through the centroids can: a ground through a model, a medium's boundary sphere around a
// scene (`everything`'s fog), whose centroids lie among the model's on every axis. Parted only
// at the leaves, such a primitive makes every node on its way down as large as itself.
constexpr int kKeys = 4;

// Finite for any box: an empty or flat one (area 0, NaN) counts as 1e-30, an overflowed one
// as the largest float.
float size_key(const Aabb& box) {
    const float a = box.half_area();
    return std::log2(a > 1e-30f ? std::min(a, std::numeric_limits<float>::max()) : 1e-30f);
}

struct BuildPrim {
    Aabb box;
    float key[kKeys];
    PrimRef ref;
};

struct BuildNode {
    Aabb box;
    std::unique_ptr<BuildNode> left, right;  // both null for a leaf
    uint32_t first = 0, count = 0;           // leaf range in the primitive array
};

// Primitives are tested block_width at a time (a leaf block of the wide layout), so the SAH
// counts blocks, not primitives: a leaf of 5 triangles costs one block test, like one of 8
// (as Embree's builders do for their 4- and 8-wide primitive blocks).
float blocks(uint32_t n, int block_width) {
    return static_cast<float>((n + uint32_t(block_width) - 1) / uint32_t(block_width));
}

// Primitives per kind. A block holds one kind, so a set costs the blocks of each kind: a
// floor quad with 7 triangles is two block tests, not one. Counting them as one made the SAH
// keep such a quad in a leaf with triangles near the root, a leaf as large as the quad that
// every ray through the floor's box tested twice.
struct KindCounts {
    std::array<uint32_t, 3> n{};

    void add(PrimRef ref) { ++n[static_cast<size_t>(ref.kind())]; }
    KindCounts& operator+=(const KindCounts& o) {
        for (size_t k = 0; k < n.size(); ++k) n[k] += o.n[k];
        return *this;
    }
    uint32_t total() const { return n[0] + n[1] + n[2]; }
    int kinds() const { return (n[0] > 0) + (n[1] > 0) + (n[2] > 0); }
    PrimKind first_kind() const {
        return n[0] > 0 ? PrimKind::Triangle : n[1] > 0 ? PrimKind::Quad : PrimKind::Sphere;
    }
    float blocks(int block_width) const {
        return wavetrace::blocks(n[0], block_width) + wavetrace::blocks(n[1], block_width) +
               wavetrace::blocks(n[2], block_width);
    }
};

// Rays walk the wide tree, not this one: the collapse folds three binary levels into one wide
// node, whose one visit tests all eight boxes. Weighted by area as the SAH weighs them, a wide
// node stands for about four binary ones (3.6-4.9 below the roots of the dragon, the bunny
// and `everything`: test Bvh.AWideNodeStandsForAboutFourBinaryNodes), so a binary node is
// charged a quarter of the traversal cost. At the full cost the binary tree kept leaves of a
// dozen triangles where splitting them would have cost no visit at all, only free slots of the
// wide node above (the McGuire box: three leaves in one node of eight slots); the collapse,
// which weighs wide nodes and leaves at their own costs, merges back what does not pay.
float binary_node_cost(const BvhBuildConfig& config) {
    return config.traversal_cost / 4.0f;
}

constexpr int kMaxBins = 64;
// Past this depth the build splits at the median, which bounds the depth of any tree by
// this, plus log2(2^30 / 2) levels of halving to leaves of two, plus the two levels that part
// a leaf's kinds: 63 < Bvh::kStackSize.
constexpr int kMedianSplitDepth = 32;

struct Bin {
    Aabb box;
    KindCounts count;
};
using Bins = std::array<std::array<Bin, kMaxBins>, kKeys>;

// The range of each key over a node's primitives.
struct KeyRange {
    float lo[kKeys], hi[kKeys];

    KeyRange() {
        std::fill(std::begin(lo), std::end(lo), kInfinity);
        std::fill(std::begin(hi), std::end(hi), -kInfinity);
    }
    void grow(const BuildPrim& p) {
        for (int k = 0; k < kKeys; ++k) {
            lo[k] = std::min(lo[k], p.key[k]);
            hi[k] = std::max(hi[k], p.key[k]);
        }
    }
    float extent(int k) const { return hi[k] - lo[k]; }
};

struct Binner {
    KeyRange keys;
    int bins;
    int used;  // keys [0, used) are binned: 3, or 4 with the size key
    // The bin of p on key k; binning and partitioning must agree on it. A key on which all
    // primitives coincide puts everything in bin 0 (it is never split on; 0 * (bins / 0)
    // would be NaN, whose conversion to int is undefined).
    int bin_of(const BuildPrim& p, int k) const {
        float extent = keys.extent(k);
        if (!(extent > 0.0f)) return 0;
        float b = (p.key[k] - keys.lo[k]) * (static_cast<float>(bins) / extent);
        return std::clamp(static_cast<int>(std::min(b, static_cast<float>(bins - 1))), 0, bins - 1);
    }
};

struct Split {
    int key;
    int split;  // primitives in bins [0, split) go left
    float cost;
};

class Builder {
  public:
    Builder(std::vector<BuildPrim>& prims, const BvhBuildConfig& config)
        : prims_(prims), config_(config), node_cost_(binary_node_cost(config)) {}

    std::unique_ptr<BuildNode> build(uint32_t begin, uint32_t end, int depth) const {
        auto node = std::make_unique<BuildNode>();
        KeyRange keys;
        KindCounts kinds;
        for (uint32_t i = begin; i < end; ++i) {
            node->box.grow(prims_[i].box);
            keys.grow(prims_[i]);
            kinds.add(prims_[i].ref);
        }
        uint32_t n = end - begin;
        auto children = [&](uint32_t mid) {
            if (n > config_.parallel_threshold) {
                tbb::parallel_invoke([&] { node->left = build(begin, mid, depth + 1); },
                                     [&] { node->right = build(mid, end, depth + 1); });
            } else {
                node->left = build(begin, mid, depth + 1);
                node->right = build(mid, end, depth + 1);
            }
            return std::move(node);
        };
        // A leaf holds one kind. Each kind is tested in blocks of its own anyway; as children
        // of their own, each block is tested only by the rays that enter its own box, where
        // one leaf of a floor quad and a few triangles made every ray through the floor's box
        // test both (the grown 10^4-triangle dragon's diffuse rays: 1.4x as fast without).
        auto make_leaf = [&] {
            if (kinds.kinds() > 1) {
                const PrimKind first = kinds.first_kind();
                auto it =
                    std::partition(prims_.begin() + begin, prims_.begin() + end,
                                   [first](const BuildPrim& p) { return p.ref.kind() == first; });
                return children(static_cast<uint32_t>(it - prims_.begin()));
            }
            node->first = begin;
            node->count = n;
            return std::move(node);
        };
        if (n == 1) return make_leaf();

        const bool fits_leaf = n <= static_cast<uint32_t>(config_.max_leaf_size);
        const int widest = max_dimension({keys.extent(0), keys.extent(1), keys.extent(2)});
        uint32_t mid = begin + n / 2;  // the median split, used when SAH cannot split
        // The size key only where a primitive's box has a quarter of the node's area, where
        // parting by size can pay; elsewhere it would add a third to the binning for little.
        const bool by_size = keys.extent(3) > 0.0f && keys.hi[3] >= size_key(node->box) - 2.0f;
        bool sah_split = (keys.extent(widest) > 0.0f || by_size) && depth < kMedianSplitDepth;
        if (sah_split) {
            Binner binner{keys, std::clamp(config_.bins, 2, kMaxBins), by_size ? 4 : 3};
            // Each thread's one set of bins: nothing between the binning and best_split runs
            // another node's build on this thread, and a node's bins are not needed after.
            thread_local Bins bins;
            bin(binner, begin, end, bins);
            Split best = best_split(binner, bins, node->box);
            float leaf_cost = config_.intersection_cost * kinds.blocks(config_.block_width);
            if (fits_leaf && leaf_cost <= best.cost) return make_leaf();
            if (best.cost < kInfinity) {
                auto it = std::partition(
                    prims_.begin() + begin, prims_.begin() + end,
                    [&](const BuildPrim& p) { return binner.bin_of(p, best.key) < best.split; });
                mid = static_cast<uint32_t>(it - prims_.begin());
            } else {
                sah_split = false;
            }
        }
        if (!sah_split) {
            // All keys coincide (or the tree is too deep): split at the median instead.
            if (fits_leaf) return make_leaf();
            std::nth_element(prims_.begin() + begin, prims_.begin() + mid, prims_.begin() + end,
                             [widest](const BuildPrim& a, const BuildPrim& b) {
                                 return a.key[widest] < b.key[widest];
                             });
        }
        return children(mid);
    }

  private:
    // The bins of [begin, end) into out's [0, binner.used) x [0, binner.bins).
    void bin(const Binner& binner, uint32_t begin, uint32_t end, Bins& out) const {
        auto bin_range = [&](uint32_t b, uint32_t e, Bins& bins) {
            for (uint32_t i = b; i < e; ++i)
                for (int k = 0; k < binner.used; ++k) {
                    Bin& bin = bins[k][binner.bin_of(prims_[i], k)];
                    bin.box.grow(prims_[i].box);
                    bin.count.add(prims_[i].ref);
                }
        };
        if (end - begin <= config_.parallel_threshold) {
            // Only the bins in use are cleared: all of them are kilobytes, and most nodes
            // are small.
            for (int k = 0; k < binner.used; ++k) std::fill_n(out[k].begin(), binner.bins, Bin{});
            bin_range(begin, end, out);
            return;
        }
        // Merging bins is exact (min/max and integer sums), so the result is the same for
        // any split of the range among threads. (While it runs, this thread may build other
        // nodes, with its own thread_local bins: `out` is written after.)
        out = tbb::parallel_reduce(
            tbb::blocked_range<uint32_t>(begin, end, 1024), Bins{},
            [&](const tbb::blocked_range<uint32_t>& r, Bins bins) {
                bin_range(r.begin(), r.end(), bins);
                return bins;
            },
            [&binner](Bins a, const Bins& b) {
                for (int k = 0; k < binner.used; ++k)
                    for (int i = 0; i < binner.bins; ++i) {
                        a[k][i].box.grow(b[k][i].box);
                        a[k][i].count += b[k][i].count;
                    }
                return a;
            });
    }

    // SAH: cost = C_trav + C_isect (A_L N_L + A_R N_R) / A (MacDonald and Booth 1990).
    Split best_split(const Binner& binner, const Bins& bins, const Aabb& box) const {
        Split best{0, 1, kInfinity};
        float inv_area = 1.0f / std::max(box.half_area(), 1e-30f);
        for (int k = 0; k < binner.used; ++k) {
            if (!(binner.keys.extent(k) > 0.0f)) continue;
            // Only the bins that hold primitives: a split between two of them costs the same
            // wherever among the empty bins between them it falls, and the first such index
            // (the one the partition uses) is the one after the left bin. A small node fills
            // few of its bins.
            std::array<int, kMaxBins> full;
            int m = 0;
            for (int i = 0; i < binner.bins; ++i)
                if (bins[k][i].count.total() > 0) full[m++] = i;
            std::array<float, kMaxBins> right_cost;
            Aabb acc;
            KindCounts count;
            for (int j = m - 1; j > 0; --j) {
                acc.grow(bins[k][full[j]].box);
                count += bins[k][full[j]].count;
                right_cost[j] = acc.half_area() * count.blocks(config_.block_width);
            }
            acc = Aabb{};
            count = KindCounts{};
            for (int j = 1; j < m; ++j) {
                acc.grow(bins[k][full[j - 1]].box);
                count += bins[k][full[j - 1]].count;
                float cost = node_cost_ + config_.intersection_cost * inv_area *
                                              (acc.half_area() * count.blocks(config_.block_width) +
                                               right_cost[j]);
                if (cost < best.cost) best = {k, full[j - 1] + 1, cost};
            }
        }
        return best;
    }

    std::vector<BuildPrim>& prims_;
    const BvhBuildConfig& config_;
    const float node_cost_;  // of a binary node
};

}  // namespace

Bvh::Bvh() : layout_(std::make_unique<BvhLayout>()) {}
Bvh::~Bvh() = default;
Bvh::Bvh(Bvh&&) noexcept = default;
Bvh& Bvh::operator=(Bvh&&) noexcept = default;

Hit Bvh::intersect(const Ray& ray) const {
    Hit hit;
    wide_intersect(layout_->wide, ray, &hit);
    return hit;
}

bool Bvh::occluded(const Ray& ray) const {
    return wide_occluded(layout_->wide, ray);
}

Hit Bvh::any_hit(const Ray& ray) const {
    Hit hit;
    wide_any_hit(layout_->wide, ray, &hit);
    return hit;
}

void Bvh::intersect_each(std::span<const Ray> rays, std::span<Hit> hits) const {
    wide_intersect_each(layout_->wide, rays.data(), std::min(rays.size(), hits.size()),
                        hits.data());
}

void Bvh::occluded_each(std::span<const Ray> rays, std::span<bool> occluded) const {
    wide_occluded_each(layout_->wide, rays.data(), std::min(rays.size(), occluded.size()),
                       occluded.data());
}

void Bvh::any_hit_each(std::span<const Ray> rays, std::span<Hit> hits) const {
    wide_any_hit_each(layout_->wide, rays.data(), std::min(rays.size(), hits.size()), hits.data());
}

void Bvh::intersect_packet(std::span<const Ray> rays, std::span<Hit> hits) const {
    wide_intersect_packet(layout_->wide, rays.data(), std::min(rays.size(), hits.size()),
                          hits.data());
}

void Bvh::occluded_packet(std::span<const Ray> rays, std::span<bool> occluded) const {
    wide_occluded_packet(layout_->wide, rays.data(), std::min(rays.size(), occluded.size()),
                         occluded.data());
}

const char* simd_target() {
    return wide_simd_target();
}

Bvh Bvh::build(const Scene& scene, const BvhBuildConfig& config) {
    auto start = std::chrono::steady_clock::now();
    Bvh bvh;
    bvh.scene_ = &scene;

    std::vector<BuildPrim> prims;
    prims.reserve(scene.primitive_count());
    auto add = [&](PrimKind kind, size_t n) {
        for (size_t i = 0; i < n; ++i) {
            PrimRef ref = PrimRef::make(kind, static_cast<uint32_t>(i));
            Aabb box = scene.prim_bounds(ref);
            const Vec3 c = box.center();
            prims.push_back({box, {c.x, c.y, c.z, size_key(box)}, ref});
        }
    };
    add(PrimKind::Triangle, scene.triangles.size());
    add(PrimKind::Quad, scene.quads.size());
    add(PrimKind::Sphere, scene.spheres.size());
    if (prims.empty()) return bvh;

    Builder builder(prims, config);
    std::unique_ptr<BuildNode> root = builder.build(0, static_cast<uint32_t>(prims.size()), 1);

    // Flatten depth-first; leaves' ranges are already contiguous in `prims` in this order.
    bvh.layout_->prims.resize(prims.size());
    for (size_t i = 0; i < prims.size(); ++i) bvh.layout_->prims[i] = prims[i].ref;
    float root_area = std::max(root->box.half_area(), 1e-30f);
    BvhStats& stats = bvh.stats_;
    auto flatten = [&](auto&& self, const BuildNode& n, int depth) -> uint32_t {
        uint32_t index = static_cast<uint32_t>(bvh.layout_->nodes.size());
        bvh.layout_->nodes.push_back({n.box.lo, 0, n.box.hi, 0});
        float rel_area = n.box.half_area() / root_area;
        if (!n.left) {
            bvh.layout_->nodes[index].offset = n.first;
            bvh.layout_->nodes[index].count = n.count;
            stats.leaves++;
            stats.depth = std::max(stats.depth, depth);
            // A leaf holds one kind: its blocks are those of its count.
            stats.sah_cost +=
                config.intersection_cost * blocks(n.count, config.block_width) * rel_area;
            return index;
        }
        stats.sah_cost += binary_node_cost(config) * rel_area;
        self(self, *n.left, depth + 1);
        uint32_t right = self(self, *n.right, depth + 1);
        bvh.layout_->nodes[index].offset = right;
        return index;
    };
    bvh.layout_->nodes.reserve(2 * prims.size());
    flatten(flatten, *root, 1);
    bvh.layout_->nodes.shrink_to_fit();

    bvh.layout_->wide =
        collapse_to_wide(scene, bvh.layout_->nodes, bvh.layout_->prims,
                         {config.traversal_cost, config.intersection_cost,
                          static_cast<uint32_t>(std::max(config.max_leaf_size, 1))});
    if (has_alpha_masks(scene)) bvh.layout_->wide.masks = &scene;

    stats.nodes = bvh.layout_->nodes.size();
    stats.bytes =
        bvh.layout_->nodes.size() * sizeof(BvhNode) + bvh.layout_->prims.size() * sizeof(PrimRef);
    stats.wide_nodes = bvh.layout_->wide.nodes.size();
    stats.wide_bytes = bvh.layout_->wide.bytes();
    stats.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return bvh;
}

}  // namespace wavetrace
