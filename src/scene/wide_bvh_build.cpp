// Collapsing the binary SAH tree into the wide traversal layout.
#include <algorithm>
#include <limits>
#include <stdexcept>

#include "scene/wide_bvh.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace {

class Collapser {
  public:
    Collapser(const Scene& scene, std::span<const BvhNode> nodes, std::span<const PrimRef> prims)
        : scene_(scene), nodes_(nodes), prims_(prims) {}

    WideBvh run() {
        if (!nodes_.empty()) node(0);
        return std::move(out_);
    }

  private:
    // A wide node's children are the binary subtree's frontier after opening, largest surface
    // area first, interior binary nodes until kWideNodeWidth children are reached: big boxes are
    // the ones most rays enter, so they are the ones worth testing side by side (Embree's
    // BVH8 collapse). A binary leaf at the root becomes a wide root with one leaf child.
    uint32_t node(uint32_t binary) {
        std::vector<uint32_t> children;
        if (nodes_[binary].is_leaf()) {
            children.push_back(binary);
        } else {
            children = {binary + 1, nodes_[binary].offset};
        }
        while (children.size() < size_t(kWideNodeWidth)) {
            int open = -1;
            float largest = -1.0f;
            for (size_t i = 0; i < children.size(); ++i) {
                const BvhNode& c = nodes_[children[i]];
                if (!c.is_leaf() && c.bounds().half_area() > largest) {
                    largest = c.bounds().half_area();
                    open = static_cast<int>(i);
                }
            }
            if (open < 0) break;
            uint32_t b = children[open];
            children[open] = b + 1;
            children.push_back(nodes_[b].offset);
        }

        uint32_t index = static_cast<uint32_t>(out_.nodes.size());
        out_.nodes.emplace_back();
        WideNode init;
        for (int i = 0; i < kWideNodeWidth; ++i) {
            for (int a = 0; a < 3; ++a) {
                init.bounds[2 * a][i] = std::numeric_limits<float>::infinity();
                init.bounds[2 * a + 1][i] = -std::numeric_limits<float>::infinity();
            }
            init.child[i] = kEmptyChild;
        }
        out_.nodes[index] = init;
        for (size_t i = 0; i < children.size(); ++i) {
            const BvhNode& c = nodes_[children[i]];
            uint32_t code = c.is_leaf() ? leaf(c) : node(children[i]);
            WideNode& w = out_.nodes[index];  // node() may have grown the vector
            for (int a = 0; a < 3; ++a) {
                w.bounds[2 * a][i] = c.lo[a];
                w.bounds[2 * a + 1][i] = c.hi[a];
            }
            w.child[i] = code;
        }
        return index;
    }

    // A binary leaf's primitives, grouped by kind into blocks of up to kLeafBlockWidth.
    uint32_t leaf(const BvhNode& leaf) {
        std::vector<LeafBlock> blocks;
        for (PrimKind kind : {PrimKind::Triangle, PrimKind::Quad, PrimKind::Sphere}) {
            std::vector<PrimRef> refs;
            for (uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i)
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
    WideBvh out_;
};

}  // namespace

WideBvh collapse_to_wide(const Scene& scene,
                         std::span<const BvhNode> nodes,
                         std::span<const PrimRef> prims) {
    return Collapser(scene, nodes, prims).run();
}

}  // namespace wavetrace
