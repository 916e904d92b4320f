// BVH invariants and agreement with brute force.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "accel/bvh_layout.h"
#include "accel/intersect.h"
#include "sampling/sampler.h"
#include "test_paths.h"
#include "util/huge_pages.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/camera.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

// Every primitive kind, some overlapping, some coincident centroids, a big enclosing sphere.
Scene mixed_scene(int n) {
    Scene s;
    Material m;
    MaterialId mat = s.add_material(m);
    auto u = [](int i, int d) { return sample_1d(7, static_cast<uint32_t>(i), 0, d); };
    std::vector<Point3> pos;
    std::vector<uint32_t> idx;
    for (int i = 0; i < n; ++i) {
        Point3 c{100 * u(i, 0), 100 * u(i, 1), 100 * u(i, 2)};
        switch (i % 3) {
            case 0:
                s.add_sphere({c, 0.5f + 2 * u(i, 3), mat, kNone});
                break;
            case 1:
                s.add_quad({c, {3 * u(i, 4) + 0.1f, 0, 0}, {0, 1, 3 * u(i, 5)}, mat, kNone});
                break;
            case 2:
                for (int k = 0; k < 3; ++k) {
                    pos.push_back(c + Vec3{4 * u(i, 6 + k), 4 * u(i, 9 + k), 4 * u(i, 12 + k)});
                    idx.push_back(static_cast<uint32_t>(pos.size() - 1));
                }
                break;
        }
    }
    for (int i = 0; i < 20; ++i)
        s.add_sphere({{50, 50, 50}, 1.0f + i, mat, kNone});  // same centroid
    s.add_mesh({}, pos, {}, {}, idx);
    return s;
}

struct Checker {
    const Bvh& bvh;
    const Scene& scene;
    std::vector<int> seen;
    int max_depth = 0;

    void visit(uint32_t index, int depth) {
        const BvhNode& node = bvh.layout().nodes[index];
        max_depth = std::max(max_depth, depth);
        if (node.is_leaf()) {
            for (uint32_t i = node.offset; i < node.offset + node.count; ++i) {
                ASSERT_LT(i, bvh.layout().prims.size());
                PrimRef p = bvh.layout().prims[i];
                ASSERT_TRUE(node.bounds().contains(scene.prim_bounds(p)));
                ++seen[i];
            }
            return;
        }
        uint32_t a = index + 1, b = node.offset;
        ASSERT_GT(b, a) << "children must follow their parent depth-first";
        ASSERT_LT(b, bvh.layout().nodes.size());
        EXPECT_TRUE(node.bounds().contains(bvh.layout().nodes[a].bounds()));
        EXPECT_TRUE(node.bounds().contains(bvh.layout().nodes[b].bounds()));
        visit(a, depth + 1);
        visit(b, depth + 1);
    }
};

}  // namespace

TEST(Bvh, EachPrimitiveInExactlyOneLeafAndBoundsNest) {
    Scene scene = mixed_scene(6000);
    Bvh bvh = Bvh::build(scene);
    ASSERT_EQ(bvh.layout().prims.size(), scene.primitive_count());
    Checker check{bvh, scene, std::vector<int>(bvh.layout().prims.size(), 0)};
    check.visit(0, 1);
    for (int count : check.seen) ASSERT_EQ(count, 1);
    // The permutation covers every primitive once.
    std::vector<int> refs_seen(scene.primitive_count(), 0);
    size_t tri = scene.triangles.size(), quad = scene.quads.size();
    for (PrimRef p : bvh.layout().prims) {
        size_t flat = p.kind() == PrimKind::Triangle ? p.index()
                      : p.kind() == PrimKind::Quad   ? tri + p.index()
                                                     : tri + quad + p.index();
        ++refs_seen[flat];
    }
    for (int count : refs_seen) ASSERT_EQ(count, 1);
    EXPECT_EQ(check.max_depth, bvh.stats().depth);
    EXPECT_LT(bvh.stats().depth, Bvh::kStackSize);
    EXPECT_EQ(bvh.stats().nodes, bvh.layout().nodes.size());
    EXPECT_EQ(bvh.stats().leaves * 2 - 1, bvh.stats().nodes);
    for (const BvhNode& n : bvh.layout().nodes) {
        if (n.is_leaf()) {
            EXPECT_LE(n.count, static_cast<uint32_t>(BvhBuildConfig{}.max_leaf_size));
        }
    }
}

// A leaf's blocks each hold one kind, so a leaf of several kinds costs a block test per kind
// for every ray entering the box of all of them: the build parts kinds into leaves of their
// own, even where the SAH would find one leaf no dearer (a floor quad and seven triangles
// lying on it make one box either way).
TEST(Bvh, EveryLeafHoldsOneKind) {
    Scene floor;
    Material m;
    const MaterialId mat = floor.add_material(m);
    floor.add_quad({{0, 0, 0}, {10, 0, 0}, {0, 0, 10}, mat, kNone});
    std::vector<Point3> pos;
    std::vector<uint32_t> idx;
    for (int i = 0; i < 7; ++i)
        for (Vec3 c : {Vec3{0, 0, 0}, Vec3{0.5f, 0, 0}, Vec3{0, 0, 0.5f}}) {
            pos.push_back(Point3{1.0f + float(i), 0, 1} + c);
            idx.push_back(static_cast<uint32_t>(pos.size() - 1));
        }
    floor.add_mesh({}, pos, {}, {}, idx);
    auto leaves_of_one_kind = [](const Scene& scene) {
        const Bvh bvh = Bvh::build(scene);
        for (const BvhNode& n : bvh.layout().nodes) {
            if (!n.is_leaf()) continue;
            for (uint32_t i = n.offset + 1; i < n.offset + n.count; ++i)
                if (bvh.layout().prims[i].kind() != bvh.layout().prims[n.offset].kind())
                    return false;
        }
        return true;
    };
    EXPECT_TRUE(leaves_of_one_kind(floor));
    EXPECT_TRUE(leaves_of_one_kind(mixed_scene(6000)));
}

// The box of slot c of a wide node (its SoA bound lanes).
Aabb slot_box(const WideNode& n, int c) {
    return {{n.bounds[0][c], n.bounds[2][c], n.bounds[4][c]},
            {n.bounds[1][c], n.bounds[3][c], n.bounds[5][c]}};
}

// The wide layout walked from its root: every primitive sits in exactly one lane of one leaf
// block, unused lanes and slots are marked, and every child box contains what lies below it.
struct WideChecker {
    const WideBvh& wide;
    const Scene& scene;
    std::vector<int> seen;  // per flat primitive index
    int max_depth = 0;

    size_t flat(PrimRef p) const {
        size_t tri = scene.triangles.size(), quad = scene.quads.size();
        return p.kind() == PrimKind::Triangle ? p.index()
               : p.kind() == PrimKind::Quad   ? tri + p.index()
                                              : tri + quad + p.index();
    }

    void visit_node(uint32_t index, int depth) {
        ASSERT_LT(index, wide.nodes.size());
        max_depth = std::max(max_depth, depth);
        const WideNode& node = wide.nodes[index];
        for (int c = 0; c < kWideNodeWidth; ++c) {
            const Aabb box = slot_box(node, c);
            uint32_t code = node.child[c];
            if (code == kEmptyChild) {
                for (int a = 0; a < 3; ++a) EXPECT_GT(box.lo[a], box.hi[a]) << "empty slot";
                continue;
            }
            if (code & kLeafChild) {
                visit_leaf(code, box);
                continue;
            }
            ASSERT_GT(code, index) << "children follow their parent";
            const WideNode& child = wide.nodes[code];
            for (int k = 0; k < kWideNodeWidth; ++k) {
                if (child.child[k] == kEmptyChild) continue;
                EXPECT_TRUE(box.contains(slot_box(child, k)));
            }
            visit_node(code, depth + 1);
        }
    }

    void visit_leaf(uint32_t code, const Aabb& box) {
        const uint32_t count = leaf_block_count(code);
        ASSERT_GE(count, 1u);
        if (leaf_kind(code) == kMixedLeaf) {
            ASSERT_LE(leaf_first(code) + count, wide.leaf_blocks.size());
        }
        for (uint32_t k = 0; k < count; ++k) {
            const LeafBlock b = leaf_block(wide, code, k);
            if (leaf_kind(code) != kMixedLeaf) {
                ASSERT_EQ(uint32_t(b.kind), leaf_kind(code));
            }
            ASSERT_GE(b.count, 1u);
            ASSERT_LE(b.count, uint32_t(kLeafBlockWidth));
            const PrimRef* refs = b.kind == PrimKind::Triangle ? wide.triangles[b.index].ref
                                  : b.kind == PrimKind::Quad   ? wide.quads[b.index].ref
                                                               : wide.spheres[b.index].ref;
            for (uint32_t l = 0; l < uint32_t(kLeafBlockWidth); ++l) {
                if (l >= b.count) {
                    EXPECT_EQ(refs[l], refs[0]) << "an unused lane repeats lane 0";
                    continue;
                }
                ASSERT_EQ(refs[l].kind(), b.kind);
                EXPECT_TRUE(box.contains(scene.prim_bounds(refs[l])));
                ++seen[flat(refs[l])];
            }
        }
    }
};

TEST(Bvh, WideLayoutHoldsEachPrimitiveOnceAndBoundsNest) {
    for (int n : {1, 7, 6000}) {
        Scene scene = mixed_scene(n);
        Bvh bvh = Bvh::build(scene);
        WideChecker check{bvh.layout().wide, scene, std::vector<int>(scene.primitive_count(), 0)};
        check.visit_node(0, 1);
        for (int count : check.seen) ASSERT_EQ(count, 1) << n << " primitives";
        EXPECT_LE(check.max_depth, bvh.stats().depth);
        EXPECT_EQ(bvh.stats().wide_nodes, bvh.layout().wide.nodes.size());
    }
}

// The expected SAH cost of a wide layout: each wide node's box area times the traversal cost,
// each leaf's box area times its blocks (the costs are BvhBuildConfig's, both 1).
double wide_sah_cost(const WideBvh& wide) {
    double cost = 0;
    auto area = [](const WideNode& n, int c) { return double(slot_box(n, c).half_area()); };
    auto visit = [&](auto&& self, uint32_t index) -> void {
        const WideNode& node = wide.nodes[index];
        for (int c = 0; c < kWideNodeWidth; ++c) {
            const uint32_t code = node.child[c];
            if (code == kEmptyChild) continue;
            if (code & kLeafChild) {
                cost += area(node, c) * leaf_block_count(code);
            } else {
                cost += area(node, c);
                self(self, code);
            }
        }
    };
    visit(visit, 0);
    return cost;
}

// The same cost for the collapse that opens the largest interior child until a node has 8
// children (Embree's BVH8 collapse), computed from the binary tree alone.
double largest_first_sah_cost(const Bvh& bvh) {
    const auto& nodes = bvh.layout().nodes;
    const auto& prims = bvh.layout().prims;
    auto blocks = [&](const BvhNode& leaf) {
        int per_kind[3] = {0, 0, 0};
        for (uint32_t i = leaf.offset; i < leaf.offset + leaf.count; ++i)
            per_kind[static_cast<int>(prims[i].kind())]++;
        int b = 0;
        for (int k : per_kind) b += (k + kLeafBlockWidth - 1) / kLeafBlockWidth;
        return b;
    };
    double cost = 0;
    auto node = [&](auto&& self, uint32_t binary) -> void {
        std::vector<uint32_t> children = {binary + 1, nodes[binary].offset};
        while (children.size() < size_t(kWideNodeWidth)) {
            int open = -1;
            float largest = -1;
            for (size_t i = 0; i < children.size(); ++i) {
                const BvhNode& c = nodes[children[i]];
                if (!c.is_leaf() && c.bounds().half_area() > largest) {
                    largest = c.bounds().half_area();
                    open = static_cast<int>(i);
                }
            }
            if (open < 0) break;
            const uint32_t b = children[open];
            children[open] = b + 1;
            children.push_back(nodes[b].offset);
        }
        for (uint32_t c : children) {
            const BvhNode& n = nodes[c];
            cost += double(n.bounds().half_area()) * (n.is_leaf() ? blocks(n) : 1);
            if (!n.is_leaf()) self(self, c);
        }
    };
    node(node, 0);
    return cost;
}

// The collapse is a dynamic program over the binary tree minimising the SAH cost of the wide
// tree, so no other collapse of the same binary tree, such as opening the largest child first,
// may cost less; on a mesh it costs clearly less (nodes filled, small subtrees made leaves).
TEST(Bvh, WideCollapseCostsNoMoreThanOpeningTheLargestChildFirst) {
    for (int n : {7, 6000}) {
        Scene scene = mixed_scene(n);
        Bvh bvh = Bvh::build(scene);
        ASSERT_FALSE(bvh.layout().nodes[0].is_leaf());
        EXPECT_LE(wide_sah_cost(bvh.layout().wide), largest_first_sah_cost(bvh) * (1 + 1e-5)) << n;
    }
    Scene dragon = load_scene(scene_path("dragon"));
    Bvh bvh = Bvh::build(dragon);
    const double dp = wide_sah_cost(bvh.layout().wide), largest = largest_first_sah_cost(bvh);
    std::printf("dragon: wide SAH cost %.4g, largest child first %.4g\n", dp, largest);
    EXPECT_LT(dp, 0.99 * largest);
}

// The binary build charges a node a quarter of a wide node's visit (bvh_build.cpp) because a
// wide node stands for about four binary ones: the binary tree's interior nodes weighted by
// their areas, as the SAH weighs them, over the wide tree's nodes weighted by theirs.
TEST(Bvh, AWideNodeStandsForAboutFourBinaryNodes) {
    for (const char* name : {"dragon", "bunny", "everything"}) {
        Scene scene = load_scene(scene_path(name));
        Bvh bvh = Bvh::build(scene);
        const auto& nodes = bvh.layout().nodes;
        // Below the roots, which are one node in either tree (and, where a primitive spans
        // the scene, as `everything`'s fog sphere does, outweigh the rest).
        double binary = 0;
        for (size_t i = 1; i < nodes.size(); ++i)
            if (!nodes[i].is_leaf()) binary += nodes[i].bounds().half_area();
        double wide = 0;  // from the slots of the wide nodes' children
        for (const WideNode& node : bvh.layout().wide.nodes)
            for (int c = 0; c < kWideNodeWidth; ++c) {
                const uint32_t code = node.child[c];
                if (code == kEmptyChild || (code & kLeafChild)) continue;
                wide += slot_box(node, c).half_area();
            }
        std::printf("%s: %.2f binary nodes per wide node, by area\n", name, binary / wide);
        EXPECT_GT(binary / wide, 3.0) << name;
        EXPECT_LT(binary / wide, 5.0) << name;
    }
}

// A ground through a model (terrain cut by a water surface, a model sunk into the floor): no
// plane through the centroids parts the ground's two triangles from the model's (their
// centroids lie among the model's on every axis); the size key does. A leaf of the model that
// kept a ground triangle would be as large as the ground, and every ray over the ground would
// test it.
TEST(Bvh, ALargeTriangleThroughAModelPartsFromIt) {
    Scene scene;
    scene.add_material(Material{});
    std::vector<Point3> pos;
    std::vector<uint32_t> idx;
    auto triangle = [&](Point3 a, Point3 b, Point3 c) {
        for (Point3 p : {a, b, c}) {
            pos.push_back(p);
            idx.push_back(static_cast<uint32_t>(pos.size() - 1));
        }
    };
    triangle({-10, 0, -10}, {10, 0, -10}, {10, 0, 10});
    triangle({-10, 0, -10}, {10, 0, 10}, {-10, 0, 10});
    // The model: small triangles scattered in [-5, 5]^3.
    auto u = [](int i, int d) { return sample_1d(11, static_cast<uint32_t>(i), 0, d); };
    Aabb model;
    for (int i = 0; i < 2000; ++i) {
        const Point3 c{10 * u(i, 0) - 5, 10 * u(i, 1) - 5, 10 * u(i, 2) - 5};
        triangle(c, c + Vec3{0.2f, 0, 0}, c + Vec3{0, 0.2f, 0.1f});
        for (int k = 0; k < 3; ++k) model.grow(pos[pos.size() - 1 - k]);
    }
    scene.add_mesh({}, pos, {}, {}, idx);

    const Bvh bvh = Bvh::build(scene);
    int mixed = 0;
    for (const BvhNode& n : bvh.layout().nodes) {
        if (!n.is_leaf()) continue;
        for (uint32_t i = n.offset; i < n.offset + n.count; ++i)
            if (bvh.layout().prims[i].index() >= 2 && !model.contains(n.bounds())) {
                ++mixed;
                break;
            }
    }
    EXPECT_EQ(mixed, 0);
}

// The wide traversal against a scalar loop over every primitive with the scalar tests of
// intersect.cpp, on every SIMD target this CPU runs: the same nearest t, the same primitive
// (ties aside) and the same barycentrics, bit for bit, so images do not depend on the CPU.
TEST(Bvh, ClosestHitMatchesBruteForceOnEverySimdTarget) {
    Scene scene = mixed_scene(3000);
    Bvh bvh = Bvh::build(scene);
    std::vector<int64_t> targets = wide_simd_targets();
    ASSERT_FALSE(targets.empty());
    for (int64_t target : targets) {
        use_wide_simd_target(target);
        SCOPED_TRACE(wide_simd_target());
        int hits = 0, ties = 0;
        for (uint32_t i = 0; i < 20000; ++i) {
            auto u = [&](int d) { return sample_1d(11, i, 0, d); };
            Point3 o{-20 + 140 * u(0), -20 + 140 * u(1), -20 + 140 * u(2)};
            Vec3 d{u(3) - 0.5f, u(4) - 0.5f, u(5) - 0.5f};
            Ray ray{o, d};
            // Brute force over every primitive.
            float best = kInfinity;
            PrimHit best_hit{};
            PrimRef best_ref;
            int at_best = 0;
            std::vector<Hit> all;  // every primitive the ray hits
            auto test = [&](bool h, const PrimHit& ph, PrimRef ref) {
                if (!h) return;
                all.push_back({ph.t, ref, ph.u, ph.v});
                if (ph.t < best) {
                    best = ph.t;
                    best_hit = ph;
                    best_ref = ref;
                    at_best = 1;
                } else if (ph.t == best) {
                    ++at_best;
                }
            };
            for (uint32_t k = 0; k < scene.triangles.size(); ++k) {
                const Triangle& t = scene.triangles[k];
                PrimHit ph;
                test(intersect_triangle(ray, scene.positions[t.v[0]], scene.positions[t.v[1]],
                                        scene.positions[t.v[2]], &ph),
                     ph, PrimRef::make(PrimKind::Triangle, k));
            }
            for (uint32_t k = 0; k < scene.quads.size(); ++k) {
                const Quad& q = scene.quads[k];
                PrimHit ph;
                test(intersect_quad(ray, q.q, q.u, q.v, &ph), ph, PrimRef::make(PrimKind::Quad, k));
            }
            for (uint32_t k = 0; k < scene.spheres.size(); ++k) {
                const Sphere& s = scene.spheres[k];
                PrimHit ph;
                test(intersect_sphere(ray, s.center, s.radius, &ph), ph,
                     PrimRef::make(PrimKind::Sphere, k));
            }
            Hit hit = bvh.intersect(ray);
            ASSERT_EQ(hit.found(), best < kInfinity) << "ray " << i;
            ASSERT_EQ(bvh.occluded(ray), best < kInfinity) << "ray " << i;
            // any_hit: one of the ray's hits, with that primitive's own numbers.
            const Hit any = bvh.any_hit(ray);
            ASSERT_EQ(any.found(), best < kInfinity) << "ray " << i;
            if (any.found()) {
                ASSERT_TRUE(std::any_of(all.begin(), all.end(),
                                        [&](const Hit& h) {
                                            return h.prim == any.prim && h.t == any.t &&
                                                   h.u == any.u && h.v == any.v;
                                        }))
                    << "ray " << i;
            }
            if (!hit.found()) continue;
            ++hits;
            ASSERT_EQ(hit.t, best) << "ray " << i;
            if (at_best > 1) {
                ++ties;
                continue;
            }
            ASSERT_EQ(hit.prim, best_ref) << "ray " << i;
            ASSERT_EQ(hit.u, best_hit.u) << "ray " << i;
            ASSERT_EQ(hit.v, best_hit.v) << "ray " << i;
        }
        std::printf("%-6s %d hits, %d ties: equal to the scalar tests\n", wide_simd_target(), hits,
                    ties);
        EXPECT_GT(hits, 1000);
        EXPECT_LT(ties, hits / 100);
    }
    use_wide_simd_target(0);
}

// Listing the targets keeps the chosen one (Highway 1.0's SupportedTargets() made the best of
// all the choice again: the bench's --simd, which lists them for Embree, was undone).
TEST(Bvh, ListingTheSimdTargetsKeepsTheChosenOne) {
    const std::vector<std::string> all = simd_targets();
    ASSERT_FALSE(all.empty());
    for (const std::string& target : all) {
        ASSERT_TRUE(use_simd_target(target)) << target;
        EXPECT_EQ(simd_targets(), all) << target;
        EXPECT_EQ(std::string(simd_target()), target);
    }
    ASSERT_TRUE(use_simd_target(""));
    EXPECT_EQ(std::string(simd_target()), all.front());
}

// Packets, and streams of single rays in one call, against single rays on the same rays, on
// every SIMD target: camera rays in 4 x 2 pixel tiles (coherent, one Woop permutation per
// packet), random rays (incoherent, mixed permutations), and shadow rays from a tile's hits
// towards one point.
TEST(Bvh, PacketsGiveTheSingleRayResultsOnEverySimdTarget) {
    for (const char* name : {"cornell", "everything", "bunny", "materials"}) {
        Scene scene = load_scene(scene_path(name));
        Bvh bvh = Bvh::build(scene);
        const int side = 64;
        CameraRays camera(scene.camera, side, side);
        std::vector<Ray> rays;
        for (int ty = 0; ty < side; ty += 2)
            for (int tx = 0; tx < side; tx += 4)
                for (int y = ty; y < ty + 2; ++y)
                    for (int x = tx; x < tx + 4; ++x)
                        rays.push_back(camera.generate(x + 0.5f, y + 0.5f, 0.5f, 0.5f));
        const size_t camera_rays = rays.size();
        Aabb box = scene.bounds();
        for (uint32_t i = 0; i < 4096; ++i) {
            auto u = [&](int dim) { return sample_1d(3, i, 0, dim); };
            Point3 o = box.lo + Vec3{u(0), u(1), u(2)} * box.extent();
            rays.push_back(Ray{o, Vec3{u(3) - 0.5f, u(4) - 0.5f, u(5) - 0.5f}});
        }
        // Shadow rays: from each camera hit towards the scene's top centre, stopping short.
        Point3 light = box.center() + Vec3{0, 0.45f * box.extent().y, 0};
        std::vector<Ray> shadows;
        for (size_t i = 0; i < camera_rays; ++i) {
            Hit h = bvh.intersect(rays[i]);
            Point3 p = h.found() ? rays[i].at(h.t * 0.999f) : rays[i].o;
            shadows.push_back(Ray{p, light - p, 1e-4f, 0.999f});
        }
        for (int64_t target : wide_simd_targets()) {
            use_wide_simd_target(target);
            SCOPED_TRACE(std::string(name) + " " + wide_simd_target());
            std::vector<Hit> packet(rays.size());
            bvh.intersect_packet(rays, packet);
            size_t hits = 0, ties = 0;
            for (size_t i = 0; i < rays.size(); ++i) {
                Hit one = bvh.intersect(rays[i]);
                ASSERT_EQ(packet[i].found(), one.found()) << "ray " << i;
                if (!one.found()) continue;
                ++hits;
                ASSERT_EQ(packet[i].t, one.t) << "ray " << i;
                if (packet[i].prim != one.prim) {
                    ++ties;  // two primitives at exactly the same t
                    continue;
                }
                ASSERT_EQ(packet[i].u, one.u) << "ray " << i;
                ASSERT_EQ(packet[i].v, one.v) << "ray " << i;
            }
            EXPECT_GT(hits, rays.size() / 4);
            EXPECT_LE(ties, hits / 100);
            std::unique_ptr<bool[]> blocked(new bool[shadows.size()]);
            bvh.occluded_packet(shadows, std::span<bool>(blocked.get(), shadows.size()));
            size_t occluded = 0;
            for (size_t i = 0; i < shadows.size(); ++i) {
                ASSERT_EQ(blocked[i], bvh.occluded(shadows[i])) << "shadow ray " << i;
                occluded += blocked[i];
            }
            EXPECT_GT(occluded, 0u);
            EXPECT_LT(occluded, shadows.size());
            // A stream of rays in one call: each ray's own single-ray result, bit for bit.
            std::vector<Hit> each(rays.size());
            bvh.intersect_each(rays, each);
            for (size_t i = 0; i < rays.size(); ++i) {
                const Hit one = bvh.intersect(rays[i]);
                ASSERT_EQ(std::memcmp(&each[i], &one, sizeof one), 0) << "ray " << i;
            }
            bvh.occluded_each(shadows, std::span<bool>(blocked.get(), shadows.size()));
            for (size_t i = 0; i < shadows.size(); ++i)
                ASSERT_EQ(blocked[i], bvh.occluded(shadows[i])) << "shadow ray " << i;
            std::vector<Hit> any(shadows.size());
            bvh.any_hit_each(shadows, any);
            for (size_t i = 0; i < shadows.size(); ++i) {
                const Hit one = bvh.any_hit(shadows[i]);
                ASSERT_EQ(std::memcmp(&any[i], &one, sizeof one), 0) << "shadow ray " << i;
            }
        }
        use_wide_simd_target(0);
    }
}

// An alpha mask cuts a surface away where its opacity is 0, keeps it where it is 1, and in
// between keeps it for that share of rays (a hash of each ray): a quad of opacity a in front of
// another quad stops a of the rays, within 4 binomial standard errors, in closest-hit and
// occlusion queries alike, and the same ray always gets the same answer.
TEST(Bvh, AlphaMasksCutSurfacesAway) {
    for (float a : {0.0f, 0.3f, 1.0f}) {
        Scene scene;
        Material front;
        front.albedo = scene.add_solid(Color(0.5f));
        front.opacity = scene.add_solid(Color(a));
        Material back;
        back.albedo = front.albedo;
        const MaterialId f = scene.add_material(front), b = scene.add_material(back);
        scene.add_quad({{-1, -1, 1}, {2, 0, 0}, {0, 2, 0}, f});
        scene.add_quad({{-1, -1, 2}, {2, 0, 0}, {0, 2, 0}, b});
        const Bvh bvh = Bvh::build(scene);
        const uint32_t n = 20000;
        uint32_t stopped = 0;
        for (uint32_t i = 0; i < n; ++i) {
            const Ray ray{{sample_1d(5, i, 0, 0) - 0.5f, sample_1d(5, i, 0, 1) - 0.5f, 0},
                          {0, 0, 1}};
            const Hit hit = bvh.intersect(ray);
            ASSERT_TRUE(hit.found());
            const bool front_hit = hit.prim == PrimRef::make(PrimKind::Quad, 0);
            stopped += front_hit;
            Ray to_back = ray;
            to_back.tmax = 1.5f;
            ASSERT_EQ(bvh.occluded(to_back), front_hit) << i;
            ASSERT_EQ(bvh.intersect(ray).prim, hit.prim) << i;
        }
        const double share = double(stopped) / n, se = std::sqrt(a * (1 - a) / n);
        std::printf("opacity %.1f: %.4f of the rays stop at the masked quad\n", a, share);
        EXPECT_NEAR(share, a, 4 * se + 1e-9);
    }
}

TEST(Bvh, BuildDoesNotDependOnThreadCount) {
    Scene scene = mixed_scene(30000);  // large enough for the parallel paths
    BvhBuildConfig config;
    config.parallel_threshold = 256;
    auto build_with = [&](int threads) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return Bvh::build(scene, config);
    };
    Bvh one = build_with(1), two = build_with(2), eight = build_with(8);
    for (const Bvh* other : {&two, &eight}) {
        ASSERT_EQ(one.layout().nodes.size(), other->layout().nodes.size());
        EXPECT_EQ(0, std::memcmp(one.layout().nodes.data(), other->layout().nodes.data(),
                                 one.layout().nodes.size() * sizeof(BvhNode)));
        EXPECT_EQ(0, std::memcmp(one.layout().prims.data(), other->layout().prims.data(),
                                 one.layout().prims.size() * sizeof(PrimRef)));
    }
}

TEST(Bvh, EmptySceneNeverHits) {
    Scene scene;
    Bvh bvh = Bvh::build(scene);
    EXPECT_FALSE(bvh.intersect({{0, 0, 0}, {0, 0, 1}}).found());
    EXPECT_FALSE(bvh.occluded({{0, 0, 0}, {0, 0, 1}}));
}

TEST(Bvh, ShippedScenesHaveSaneTrees) {
    for (const char* name : {"cornell", "bunny", "dragon", "everything"}) {
        Scene scene = load_scene(scene_path(name));
        Bvh bvh = Bvh::build(scene);
        const BvhStats& s = bvh.stats();
        std::printf("%-10s %8zu prims %8zu nodes depth %2d SAH %.2f\n", name,
                    scene.primitive_count(), s.nodes, s.depth, s.sah_cost);
        EXPECT_EQ(bvh.layout().prims.size(), scene.primitive_count());
        EXPECT_LT(s.depth, Bvh::kStackSize);
        EXPECT_GT(s.sah_cost, 0.0f);
    }
}

namespace {

// The VmFlags of the mapping that holds p (/proc/self/smaps), empty where none does.
std::string mapping_flags(const void* p) {
    std::ifstream smaps("/proc/self/smaps");
    const uintptr_t a = reinterpret_cast<uintptr_t>(p);
    bool inside = false;
    for (std::string line; std::getline(smaps, line);) {
        unsigned long lo = 0, hi = 0;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2)
            inside = a >= lo && a < hi;
        else if (inside && line.rfind("VmFlags:", 0) == 0)
            return line.substr(8);
    }
    return "";
}

}  // namespace

// Arrays of 2 MiB or more start on a huge-page boundary in a mapping advised for huge pages
// (the "hg" flag), and keep their contents as they grow; smaller ones keep their type's
// alignment. The wide BVH's arrays are such arrays.
TEST(Bvh, LargeArraysAskForHugePages) {
    std::ifstream probe("/proc/self/smaps");
    if (!probe) GTEST_SKIP() << "no /proc/self/smaps";
    std::vector<uint32_t, HugePageAllocator<uint32_t>> big;
    for (uint32_t i = 0; i < (3u << 20) / 4; ++i) big.push_back(i);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(big.data()) % kHugePageBytes, 0u);
    EXPECT_NE(mapping_flags(big.data()).find(" hg"), std::string::npos)
        << mapping_flags(big.data());
    for (uint32_t i = 0; i < big.size(); i += 4099) ASSERT_EQ(big[i], i);
    std::vector<WideNode, HugePageAllocator<WideNode>> small(3);
    EXPECT_EQ(reinterpret_cast<uintptr_t>(small.data()) % alignof(WideNode), 0u);
    static_assert(
        std::is_same_v<decltype(WideBvh::nodes)::allocator_type, HugePageAllocator<WideNode>>);
    static_assert(std::is_same_v<decltype(WideBvh::triangles)::allocator_type,
                                 HugePageAllocator<TriangleBlock>>);
}
