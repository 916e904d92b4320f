// Collapsing the binary SAH tree into the wide traversal layout: which binary subtrees become
// wide nodes, which become leaves, and which share their parent's slots.
#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

#include "accel/wide_bvh.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

class Collapser {
  public:
    Collapser(const Scene& scene,
              std::span<const BvhNode> nodes,
              std::span<const PrimRef> prims,
              const WideCollapseCosts& costs)
        : scene_(scene), nodes_(nodes), prims_(prims), costs_(costs) {}

    WideBvh run() {
        if (nodes_.empty()) return std::move(out_);
        plan();
        // The root is a wide node even where the whole scene is one leaf.
        const Choice& root = choice_[0];
        if (!root.leaf) {
            wide_node(0);
        } else {
            out_.nodes.push_back(empty_node());
            const uint32_t code = leaf(first_[0], count_[0]);
            set_child(0, 0, 0, code);
        }
        return std::move(out_);
    }

  private:
    // ---- the collapse: which binary subtrees become wide nodes, leaves, or share a parent ----
    // Dynamic programming over the binary tree (Ylitie, Karras and Laine, "Efficient Incoherent
    // Ray Traversal on GPUs Through Compressed Wide BVHs", HPG 2017, §4.1), with the SAH as the
    // cost: cost[n][i] is the least expected cost of binary subtree n spread over at most i
    // slots of a wide node (i = 1: n itself in one slot, as a leaf or as a wide node of its
    // own). A wide node costs its box's area times the traversal cost (one visit tests all its
    // children's boxes); a leaf its area times the blocks it holds. Unlike opening the largest
    // child first until 8 are found, this fills nodes where that pays and makes whole subtrees
    // leaves where their primitives share blocks.
    struct Choice {
        float cost[kWideNodeWidth + 1];     // [i], i = 1 .. kWideNodeWidth
        uint8_t split[kWideNodeWidth + 1];  // [i >= 2]: slots of the left child; 0: use i - 1
        uint8_t node_split;                 // as a wide node: slots of the left child
        bool leaf;                          // [1]: a leaf rather than a wide node
    };

    float leaf_cost(uint32_t n, const uint32_t kinds[3]) const {
        float blocks = 0;
        for (int k = 0; k < 3; ++k)
            blocks += static_cast<float>((kinds[k] + kLeafBlockWidth - 1) / kLeafBlockWidth);
        return nodes_[n].bounds().half_area() * costs_.intersection * blocks;
    }

    void plan() {
        const size_t n_nodes = nodes_.size();
        choice_.assign(n_nodes, {});
        first_.assign(n_nodes, 0);
        count_.assign(n_nodes, 0);
        std::vector<std::array<uint32_t, 3>> kinds(n_nodes, {0, 0, 0});
        // Children come after their parent in the depth-first order: go backwards.
        for (size_t idx = n_nodes; idx-- > 0;) {
            const uint32_t n = static_cast<uint32_t>(idx);
            const BvhNode& b = nodes_[n];
            Choice& c = choice_[n];
            if (b.is_leaf()) {
                for (uint32_t i = b.offset; i < b.offset + b.count; ++i)
                    kinds[n][static_cast<size_t>(prims_[i].kind())]++;
                first_[n] = b.offset;
                count_[n] = b.count;
                c.leaf = true;
                c.cost[1] = leaf_cost(n, kinds[n].data());
                for (int i = 2; i <= kWideNodeWidth; ++i) {
                    c.cost[i] = c.cost[1];
                    c.split[i] = 0;
                }
                continue;
            }
            const uint32_t l = n + 1, r = b.offset;
            for (int k = 0; k < 3; ++k) kinds[n][k] = kinds[l][k] + kinds[r][k];
            first_[n] = first_[l];
            count_[n] = count_[l] + count_[r];
            // The two children over j slots.
            float spread[kWideNodeWidth + 1];
            uint8_t best_split[kWideNodeWidth + 1];
            for (int j = 2; j <= kWideNodeWidth; ++j) {
                spread[j] = std::numeric_limits<float>::infinity();
                best_split[j] = 1;  // stays valid where every cost is infinite
                for (int k = 1; k < j; ++k) {
                    const float cost = choice_[l].cost[k] + choice_[r].cost[j - k];
                    if (cost < spread[j]) {
                        spread[j] = cost;
                        best_split[j] = static_cast<uint8_t>(k);
                    }
                }
            }
            const float as_node =
                b.bounds().half_area() * costs_.traversal + spread[kWideNodeWidth];
            const float as_leaf = count_[n] <= costs_.max_leaf_size
                                      ? leaf_cost(n, kinds[n].data())
                                      : std::numeric_limits<float>::infinity();
            c.leaf = as_leaf <= as_node;
            c.node_split = best_split[kWideNodeWidth];
            c.cost[1] = std::min(as_leaf, as_node);
            for (int i = 2; i <= kWideNodeWidth; ++i) {
                const bool fewer = c.cost[i - 1] <= spread[i];
                c.cost[i] = fewer ? c.cost[i - 1] : spread[i];
                c.split[i] = fewer ? 0 : best_split[i];
            }
        }
    }

    // The binary nodes that take the slots of subtree n spread over at most i slots.
    void slots(uint32_t n, int i, std::vector<uint32_t>& out) const {
        while (i > 1 && choice_[n].split[i] == 0) --i;
        if (i == 1) {
            out.push_back(n);
            return;
        }
        const int k = choice_[n].split[i];
        slots(n + 1, k, out);
        slots(nodes_[n].offset, i - k, out);
    }

    static WideNode empty_node() {
        WideNode init;
        for (int i = 0; i < kWideNodeWidth; ++i) {
            for (int a = 0; a < 3; ++a) {
                init.bounds[2 * a][i] = std::numeric_limits<float>::infinity();
                init.bounds[2 * a + 1][i] = -std::numeric_limits<float>::infinity();
            }
            init.child[i] = kEmptyChild;
        }
        return init;
    }

    void set_child(uint32_t index, int slot, uint32_t binary, uint32_t code) {
        const BvhNode& c = nodes_[binary];
        WideNode& w = out_.nodes[index];
        for (int a = 0; a < 3; ++a) {
            w.bounds[2 * a][slot] = c.lo[a];
            w.bounds[2 * a + 1][slot] = c.hi[a];
        }
        w.child[slot] = code;
    }

    // The wide node of binary node n (chosen as a node): its children are n's children spread
    // over all slots.
    uint32_t wide_node(uint32_t n) {
        std::vector<uint32_t> children;
        slots(n + 1, choice_[n].node_split, children);
        slots(nodes_[n].offset, kWideNodeWidth - choice_[n].node_split, children);
        const uint32_t index = static_cast<uint32_t>(out_.nodes.size());
        out_.nodes.push_back(empty_node());
        for (size_t i = 0; i < children.size(); ++i) {
            const uint32_t c = children[i];
            const uint32_t code = choice_[c].leaf ? leaf(first_[c], count_[c]) : wide_node(c);
            set_child(index, static_cast<int>(i), c, code);
        }
        return index;
    }

    // A leaf of primitives [offset, offset + count_prims) (a binary subtree's), grouped by kind
    // into blocks of up to kLeafBlockWidth.
    uint32_t leaf(uint32_t offset, uint32_t count_prims) {
        std::vector<LeafBlock> blocks;
        for (PrimKind kind : {PrimKind::Triangle, PrimKind::Quad, PrimKind::Sphere}) {
            std::vector<PrimRef> refs;
            for (uint32_t i = offset; i < offset + count_prims; ++i)
                if (prims_[i].kind() == kind) refs.push_back(prims_[i]);
            for (size_t start = 0; start < refs.size(); start += kLeafBlockWidth) {
                size_t n = std::min(refs.size() - start, size_t(kLeafBlockWidth));
                std::span<const PrimRef> lanes(refs.data() + start, n);
                blocks.push_back({kind, static_cast<uint32_t>(n), block(kind, lanes)});
            }
        }
        const uint32_t count = static_cast<uint32_t>(blocks.size());
        bool one_kind = true;
        for (const LeafBlock& b : blocks) one_kind = one_kind && b.kind == blocks[0].kind;
        // One kind: its blocks were appended one after the other to the kind's array.
        const uint32_t kind = one_kind ? static_cast<uint32_t>(blocks[0].kind) : kMixedLeaf;
        const uint32_t first =
            one_kind ? blocks[0].index : static_cast<uint32_t>(out_.leaf_blocks.size());
        if (!one_kind)
            out_.leaf_blocks.insert(out_.leaf_blocks.end(), blocks.begin(), blocks.end());
        if (count > kMaxLeafBlocks || first > kLeafFirstMask)
            throw std::length_error("BVH leaf does not fit the wide layout");
        return kLeafChild | kind << kLeafKindShift | count << kLeafCountShift | first;
    }

    uint32_t block(PrimKind kind, std::span<const PrimRef> refs) {
        // Lane i < refs.size() holds primitive i; the rest repeat lane 0, reference included.
        auto lane_ref = [&](int i) { return refs[size_t(i) < refs.size() ? i : 0]; };
        switch (kind) {
            case PrimKind::Triangle: {
                TriangleBlock& b = out_.triangles.emplace_back();
                for (int i = 0; i < kLeafBlockWidth; ++i) {
                    const Triangle& t = scene_.triangles[lane_ref(i).index()];
                    for (int vtx = 0; vtx < 3; ++vtx)
                        for (int a = 0; a < 3; ++a) b.p[vtx][a][i] = scene_.positions[t.v[vtx]][a];
                    b.ref[i] = lane_ref(i);
                }
                return static_cast<uint32_t>(out_.triangles.size() - 1);
            }
            case PrimKind::Quad: {
                QuadBlock& b = out_.quads.emplace_back();
                for (int i = 0; i < kLeafBlockWidth; ++i) {
                    const Quad& q = scene_.quads[lane_ref(i).index()];
                    Vec3 n = cross(q.u, q.v);
                    Vec3 w = n / dot(n, n);
                    for (int a = 0; a < 3; ++a) {
                        b.q[a][i] = q.q[a];
                        b.u[a][i] = q.u[a];
                        b.v[a][i] = q.v[a];
                        b.n[a][i] = n[a];
                        b.w[a][i] = w[a];
                    }
                    b.ref[i] = lane_ref(i);
                }
                return static_cast<uint32_t>(out_.quads.size() - 1);
            }
            case PrimKind::Sphere: {
                SphereBlock& b = out_.spheres.emplace_back();
                for (int i = 0; i < kLeafBlockWidth; ++i) {
                    const Sphere& s = scene_.spheres[lane_ref(i).index()];
                    for (int a = 0; a < 3; ++a) b.c[a][i] = s.center[a];
                    b.r[i] = s.radius;
                    b.ref[i] = lane_ref(i);
                }
                return static_cast<uint32_t>(out_.spheres.size() - 1);
            }
        }
        return 0;
    }

    const Scene& scene_;
    std::span<const BvhNode> nodes_;
    std::span<const PrimRef> prims_;
    WideCollapseCosts costs_;
    std::vector<Choice> choice_;
    std::vector<uint32_t> first_, count_;  // each binary subtree's primitives in prims_
    WideBvh out_;
};

}  // namespace

WideBvh collapse_to_wide(const Scene& scene,
                         std::span<const BvhNode> nodes,
                         std::span<const PrimRef> prims,
                         const WideCollapseCosts& costs) {
    return Collapser(scene, nodes, prims, costs).run();
}

}  // namespace wavetrace
