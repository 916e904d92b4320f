// Packet traversal of the wide BVH: up to a vector's width of coherent rays walk the tree
// together, with the SIMD tests of wide_leaf_tests-inl.h; compiled for every target Highway
// knows and dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "accel/wide_bvh_packets.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#include <algorithm>
#include <bit>
#include <new>

#include "accel/wide_bvh.h"
#include "accel/wide_leaf_tests-inl.h"
#include "accel/wide_ray_walk-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
// ---- packets: up to Lanes(D) coherent rays walk the tree together ------------------------
// One lane per ray (Wald, Slusallek, Benthin and Wagner, "Interactive Rendering with Coherent
// Ray Tracing", 2001; over a wide tree as in Embree's hybrid traversal): a node's children are
// tested one after the other against all rays at once, a child is entered when any active ray
// enters it, nearest first by the smallest entry distance among those rays. Each primitive of a
// leaf is tested against all rays at once with the lane functions above, so every ray gets the
// hit the single-ray traversal gives it (ties aside). Rays whose major axes differ (Woop's
// permutation is then not uniform over the packet) test triangle blocks one ray at a time.
// A subtree that at most kLoneRays of the packet's rays enter is walked by each of them alone
// (wide_ray_walk-inl.h), as in Embree's hybrid traversal (Benthin, Wald, Woop, Ernst and Mark,
// "Combining Single and Packet-Ray Tracing for Arbitrary Ray Distributions on the Intel MIC
// Architecture", TVCG 2012): where the rays diverge, a packet would test every box and
// primitive for all lanes to serve one or two.
inline constexpr int kLoneRays = 2;

// Lane l alone.
HWY_INLINE M LaneMask(D d, size_t l) {
    return hn::And(hn::FirstN(d, l + 1), hn::Not(hn::FirstN(d, l)));
}

template <bool AnyHit>
HWY_INLINE void TraversePacket(
    const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits, bool* occluded) {
    const D d;
    const size_t N = hn::Lanes(d);
    HWY_ALIGN float a[12][kLeafBlockWidth];  // the first N lanes of each row, all that is loaded
    // Each lane's single-ray constants, constructed in place: a RayLanes assigned from a
    // temporary is copied in wide words just after its fields were stored one by one, and each
    // such load waits for the stores to retire (a failed store-to-load forwarding) per ray.
    union Singles {
        Singles() {}
        RayLanes at[kLeafBlockWidth];
    } singles;
    RayLanes* const single = singles.at;
    bool uniform = true;
    for (size_t l = 0; l < N; ++l) {
        const Ray& r = rays[l < n ? l : 0];
        new (&single[l]) RayLanes(r);
        uniform = uniform && single[l].tri.kz == single[0].tri.kz;
        for (int k = 0; k < 3; ++k) {
            a[k][l] = r.o[k];
            a[3 + k][l] = r.d[k];
            a[6 + k][l] = single[l].inv_d[k];
        }
        a[9][l] = r.tmin;
        a[10][l] = r.tmax;
        a[11][l] = dot(r.d, r.d);
    }
    const V o[3] = {hn::Load(d, a[0]), hn::Load(d, a[1]), hn::Load(d, a[2])};
    const V dir[3] = {hn::Load(d, a[3]), hn::Load(d, a[4]), hn::Load(d, a[5])};
    const V inv[3] = {hn::Load(d, a[6]), hn::Load(d, a[7]), hn::Load(d, a[8])};
    const V tmin = hn::Load(d, a[9]), dd = hn::Load(d, a[11]);
    V tmax = hn::Load(d, a[10]);
    V hit_u = hn::Zero(d), hit_v = hn::Zero(d);
    PrimRef hit_prim[kLeafBlockWidth];
    M active = hn::FirstN(d, n);
    uint32_t found = 0;

    // Woop's per-ray constants in lanes, for packets with one permutation.
    const int kx = single[0].tri.kx, ky = single[0].tri.ky, kz = single[0].tri.kz;
    HWY_ALIGN float shear[3][kLeafBlockWidth];
    for (size_t l = 0; l < N; ++l) {
        shear[0][l] = single[l].tri.sx;
        shear[1][l] = single[l].tri.sy;
        shear[2][l] = single[l].tri.sz;
    }
    const V sx = hn::Load(d, shear[0]), sy = hn::Load(d, shear[1]), sz = hn::Load(d, shear[2]);

    // Records lanes `ok` as hitting primitive `ref` at t (closest hit: a later primitive at
    // equal t wins, as in the single-ray traversal); any-hit: retires them.
    // `masked`: the hits still go through the alpha masks (else the caller did that).
    auto record = [&](M ok, PrimRef ref, V t, V u, V v, bool masked = true) {
        ok = hn::And(ok, active);
        if (hn::AllFalse(d, ok)) return;
        uint32_t bits = MaskBits(d, ok);
        if (masked && bvh.masks != nullptr) {
            HWY_ALIGN float lt[kLeafBlockWidth], lu[kLeafBlockWidth], lv[kLeafBlockWidth],
                lmax[kLeafBlockWidth];
            hn::Store(t, d, lt);
            hn::Store(u, d, lu);
            hn::Store(v, d, lv);
            hn::Store(tmax, d, lmax);
            HWY_ALIGN float keep[kLeafBlockWidth] = {};
            for (uint32_t b = bits; b != 0; b &= b - 1) {
                const uint32_t l = static_cast<uint32_t>(__builtin_ctz(b));
                if (uncut_hit(bvh, ref, &lt[l], lu[l], lv[l], rays[l < n ? l : 0], lmax[l]))
                    keep[l] = 1.0f;
                else
                    bits &= ~(1u << l);
            }
            if (bits == 0) return;
            ok = hn::And(ok, hn::Gt(hn::Load(d, keep), hn::Zero(d)));
            t = hn::Load(d, lt);
        }
        found |= bits;
        if constexpr (AnyHit) {
            active = hn::AndNot(ok, active);
            return;
        }
        tmax = hn::IfThenElse(ok, t, tmax);
        hit_u = hn::IfThenElse(ok, u, hit_u);
        hit_v = hn::IfThenElse(ok, v, hit_v);
        for (uint32_t b = bits; b != 0; b &= b - 1) hit_prim[__builtin_ctz(b)] = ref;
    };

    struct Entry {
        uint32_t code;
        float t_entry;  // the smallest entry distance among the rays that enter it
        uint32_t rays;  // a bit per ray that enters it
    };
    Entry stack[Bvh::kStackSize * (kWideNodeWidth - 1) + 1];
    int sp = 0;
    uint32_t code = 0, code_rays = MaskBits(d, active);
    const V inf = hn::Set(d, kInfinity);
    const V widen = hn::Set(d, 1.0f + 2.0f * gamma(3));

    for (;;) {
        const uint32_t walkers = code_rays & MaskBits(d, active);
        if (std::popcount(walkers) <= kLoneRays) {
            HWY_ALIGN float lane_t[kLeafBlockWidth];
            hn::Store(tmax, d, lane_t);
            for (uint32_t b = walkers; b != 0; b &= b - 1) {
                const uint32_t l = static_cast<uint32_t>(__builtin_ctz(b));
                Hit h;
                if (WalkSubtree<AnyHit>(bvh, single[l], code, &lane_t[l], &h)) {
                    const M lane = LaneMask(d, l);
                    record(lane, h.prim, hn::Set(d, h.t), hn::Set(d, h.u), hn::Set(d, h.v), false);
                }
            }
        } else if (!(code & kLeafChild)) {
            const WideNode& node = bvh.nodes[code];
            Entry hit_children[kWideNodeWidth];
            int count = 0;
            for (int c = 0; c < kWideNodeWidth && node.child[c] != kEmptyChild; ++c) {
                // The slab test per ray, as in BoxTest (min/max in place of the sign choice
                // gives the same two distances per axis).
                V t_near = tmin, t_far = inf;
                for (int k = 0; k < 3; ++k) {
                    const V t0 = hn::Mul(hn::Sub(hn::Set(d, node.bounds[2 * k][c]), o[k]), inv[k]);
                    const V t1 =
                        hn::Mul(hn::Sub(hn::Set(d, node.bounds[2 * k + 1][c]), o[k]), inv[k]);
                    t_near = hn::Max(t_near, hn::Min(t0, t1));
                    t_far = hn::Min(t_far, hn::Max(t0, t1));
                }
                const M enter =
                    hn::And(active, hn::Le(t_near, hn::Min(hn::Mul(t_far, widen), tmax)));
                if (hn::AllFalse(d, enter)) continue;
                const float t_min =
                    hn::GetLane(hn::MinOfLanes(d, hn::IfThenElse(enter, t_near, inf)));
                hit_children[count++] = {node.child[c], t_min, MaskBits(d, enter)};
            }
            if (count > 0) {
                // Farthest first onto the stack; take the nearest now.
                for (int i = 1; i < count; ++i)
                    for (int j = i; j > 0 && hit_children[j - 1].t_entry < hit_children[j].t_entry;
                         --j)
                        std::swap(hit_children[j - 1], hit_children[j]);
                for (int i = 0; i < count - 1; ++i) stack[sp++] = hit_children[i];
                code = hit_children[count - 1].code;
                code_rays = hit_children[count - 1].rays;
                continue;
            }
        } else {
            for (uint32_t blk = 0, blocks = leaf_block_count(code); blk < blocks; ++blk) {
                const LeafBlock lb = leaf_block(bvh, code, blk);
                if (lb.kind == PrimKind::Triangle && !uniform) {
                    // Rays with different permutations: one ray at a time against the block.
                    const TriangleBlock& b = bvh.triangles[lb.index];
                    HWY_ALIGN float lane_t[kLeafBlockWidth];
                    hn::Store(tmax, d, lane_t);
                    const uint32_t act = MaskBits(d, active);
                    for (size_t l = 0; l < N; ++l) {
                        if (!(act >> l & 1)) continue;
                        BlockHits bh;
                        TriangleTest(b, lb.count, single[l], lane_t[l], &bh);
                        if (bvh.masks != nullptr && bh.bits != 0)
                            bh.bits = uncut_hits(bvh, bh.bits, b.ref, bh.t, bh.u, bh.v, rays[l],
                                                 lane_t[l]);
                        for (uint32_t bits = bh.bits; bits != 0; bits &= bits - 1) {
                            const uint32_t j = static_cast<uint32_t>(__builtin_ctz(bits));
                            if (bh.t[j] > lane_t[l]) continue;
                            lane_t[l] = bh.t[j];
                            const M lane = LaneMask(d, l);
                            record(lane, b.ref[j], hn::Set(d, bh.t[j]), hn::Set(d, bh.u[j]),
                                   hn::Set(d, bh.v[j]), false);
                            if (AnyHit) break;
                        }
                    }
                } else {
                    for (uint32_t j = 0; j < lb.count; ++j) {
                        V t = hn::Zero(d), u = t, v = t;
                        M ok;
                        PrimRef ref;
                        if (lb.kind == PrimKind::Triangle) {
                            const TriangleBlock& b = bvh.triangles[lb.index];
                            V px[3], py[3], pz[3];
                            for (int vtx = 0; vtx < 3; ++vtx) {
                                px[vtx] = hn::Sub(hn::Set(d, b.p[vtx][kx][j]), o[kx]);
                                py[vtx] = hn::Sub(hn::Set(d, b.p[vtx][ky][j]), o[ky]);
                                pz[vtx] = hn::Sub(hn::Set(d, b.p[vtx][kz][j]), o[kz]);
                            }
                            ok = TriangleLanes(d, px, py, pz, sx, sy, sz, tmin, tmax, active, &t,
                                               &u, &v);
                            ref = b.ref[j];
                        } else if (lb.kind == PrimKind::Quad) {
                            const QuadBlock& b = bvh.quads[lb.index];
                            const QuadLanesIn p{hn::Set(d, b.q[0][j]), hn::Set(d, b.q[1][j]),
                                                hn::Set(d, b.q[2][j]), hn::Set(d, b.u[0][j]),
                                                hn::Set(d, b.u[1][j]), hn::Set(d, b.u[2][j]),
                                                hn::Set(d, b.v[0][j]), hn::Set(d, b.v[1][j]),
                                                hn::Set(d, b.v[2][j]), hn::Set(d, b.n[0][j]),
                                                hn::Set(d, b.n[1][j]), hn::Set(d, b.n[2][j]),
                                                hn::Set(d, b.w[0][j]), hn::Set(d, b.w[1][j]),
                                                hn::Set(d, b.w[2][j])};
                            ok = QuadLanes(d, p, o[0], o[1], o[2], dir[0], dir[1], dir[2], tmin,
                                           tmax, active, &t, &u, &v);
                            ref = b.ref[j];
                        } else {
                            const SphereBlock& b = bvh.spheres[lb.index];
                            ok = SphereLanes(d, hn::Set(d, b.c[0][j]), hn::Set(d, b.c[1][j]),
                                             hn::Set(d, b.c[2][j]), hn::Set(d, b.r[j]), o[0], o[1],
                                             o[2], dir[0], dir[1], dir[2], dd, tmin, tmax, active,
                                             &t);
                            ref = b.ref[j];
                        }
                        record(ok, ref, t, u, v);
                    }
                }
                if (AnyHit && hn::AllFalse(d, active)) break;
            }
            if (AnyHit && hn::AllFalse(d, active)) break;
        }
        // Pop the next subtree that some active ray may still find a closer hit in.
        const float tmax_all =
            hn::GetLane(hn::MaxOfLanes(d, hn::IfThenElse(active, tmax, hn::Set(d, -kInfinity))));
        bool more = false;
        while (sp > 0) {
            const Entry e = stack[--sp];
            if (e.t_entry <= tmax_all) {
                code = e.code;
                code_rays = e.rays;
                more = true;
                break;
            }
        }
        if (!more) break;
    }

    HWY_ALIGN float out_t[kLeafBlockWidth], out_u[kLeafBlockWidth], out_v[kLeafBlockWidth];
    hn::Store(tmax, d, out_t);
    hn::Store(hit_u, d, out_u);
    hn::Store(hit_v, d, out_v);
    for (size_t l = 0; l < n; ++l) {
        const bool f = found >> l & 1;
        if (occluded) occluded[l] = f;
        if (hits) hits[l] = f ? Hit{out_t[l], hit_prim[l], out_u[l], out_v[l]} : Hit{};
    }
}

void IntersectPacket(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits) {
    const size_t N = hn::Lanes(D());
    if (bvh.nodes.empty()) {
        for (size_t i = 0; i < n; ++i) hits[i] = Hit{};
        return;
    }
    for (size_t i = 0; i < n; i += N)
        TraversePacket<false>(bvh, rays + i, std::min(N, n - i), hits + i, nullptr);
}

void OccludedPacket(const WideBvh& bvh, const Ray* rays, size_t n, bool* occluded) {
    const size_t N = hn::Lanes(D());
    if (bvh.nodes.empty()) {
        for (size_t i = 0; i < n; ++i) occluded[i] = false;
        return;
    }
    for (size_t i = 0; i < n; i += N)
        TraversePacket<true>(bvh, rays + i, std::min(N, n - i), nullptr, occluded + i);
}
}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace wavetrace {

HWY_EXPORT(IntersectPacket);
HWY_EXPORT(OccludedPacket);

void wide_intersect_packet(const WideBvh& bvh, const Ray* rays, size_t n, Hit* hits) {
    HWY_DYNAMIC_DISPATCH(IntersectPacket)(bvh, rays, n, hits);
}

void wide_occluded_packet(const WideBvh& bvh, const Ray* rays, size_t n, bool* occluded) {
    HWY_DYNAMIC_DISPATCH(OccludedPacket)(bvh, rays, n, occluded);
}

}  // namespace wavetrace
#endif  // HWY_ONCE
