// The wide BVH's SIMD tests, per target (see math/lanes-inl.h): a ray's constants in lanes,
// the 8-wide box test, and the triangle, quad and sphere tests over a leaf block, shared by
// the single-ray traversal (wide_bvh_traverse.cpp) and the packet traversal
// (wide_bvh_packets.cpp).
//
// Every lane performs exactly the float operations of the scalar tests in intersect.cpp, in
// the same order and without fused multiply-adds (-ffp-contract=off, and no MulAdd here), so a
// ray gets the same t, u, v from a block as from intersect_triangle / intersect_quad /
// intersect_sphere, on every target: images do not depend on the CPU, and the watertightness
// of Woop's test carries over unchanged.
#if defined(WAVETRACE_ACCEL_WIDE_LEAF_TESTS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_ACCEL_WIDE_LEAF_TESTS_INL_H_
#undef WAVETRACE_ACCEL_WIDE_LEAF_TESTS_INL_H_
#else
#define WAVETRACE_ACCEL_WIDE_LEAF_TESTS_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>

#include "accel/intersect.h"
#include "accel/wide_bvh.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Up to a node's or a block's width in float lanes: one vector per node or block on AVX2 and
// AVX-512, two on SSE4 and NEON.
using DNode = hn::CappedTag<float, kWideNodeWidth>;
using D = hn::CappedTag<float, kLeafBlockWidth>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

// Per-ray constants of the box test and of Woop's triangle test.
struct RayLanes {
    Ray ray;
    float inv_d[3];
    int near_lo[3];  // per axis: bounds row of the near plane (lo for inv_d >= 0, else hi)
    TriangleRay tri;

    explicit RayLanes(const Ray& r) : ray(r), tri(r) {
        for (int a = 0; a < 3; ++a) {
            // 1/d with zero components replaced by a huge finite value of the same sign: the
            // slab distances stay finite, so the box test needs no NaN handling.
            float d = r.d[a];
            inv_d[a] = std::fabs(d) > 1e-30f ? 1.0f / d : std::copysign(1e30f, d);
            near_lo[a] = inv_d[a] < 0 ? 1 : 0;
        }
    }
};

// The slab test of all children of a node: entry distances into `t_entry` and a bit per child
// whose box the ray enters within [tmin, tmax]. The exit distance is widened by 1 + 2 gamma(3)
// so that rounding never culls a box the ray really touches (Ize, "Robust BVH Ray Traversal",
// JCGT 2(2), 2013).
HWY_INLINE uint32_t BoxTest(const WideNode& node, const RayLanes& r, float tmax, float* t_entry) {
    const DNode d;
    using VN = hn::Vec<DNode>;
    using MN = hn::Mask<DNode>;
    const size_t N = hn::Lanes(d);
    uint32_t bits = 0;
    const VN widen = hn::Set(d, 1.0f + 2.0f * gamma(3));
    const VN tmin_v = hn::Set(d, r.ray.tmin), tmax_v = hn::Set(d, tmax);
    for (size_t i = 0; i < size_t(kWideNodeWidth); i += N) {
        VN t_near = tmin_v, t_far = hn::Set(d, kInfinity);
        for (int a = 0; a < 3; ++a) {
            const VN o = hn::Set(d, r.ray.o[a]), inv = hn::Set(d, r.inv_d[a]);
            const VN near = hn::Load(d, node.bounds[2 * a + r.near_lo[a]] + i);
            const VN far = hn::Load(d, node.bounds[2 * a + 1 - r.near_lo[a]] + i);
            t_near = hn::Max(t_near, hn::Mul(hn::Sub(near, o), inv));
            t_far = hn::Min(t_far, hn::Mul(hn::Sub(far, o), inv));
        }
        t_far = hn::Mul(t_far, widen);
        const MN hit = hn::Le(t_near, hn::Min(t_far, tmax_v));
        hn::Store(t_near, d, t_entry + i);
        uint8_t mask_bytes[8] = {};
        hn::StoreMaskBits(d, hit, mask_bytes);
        bits |= uint32_t(mask_bytes[0]) << i;
    }
    return bits;
}

// The lanes' results of one block: which lanes hit within [tmin, tmax], with t, u, v.
struct BlockHits {
    uint32_t bits;
    HWY_ALIGN float t[kLeafBlockWidth];
    HWY_ALIGN float u[kLeafBlockWidth];
    HWY_ALIGN float v[kLeafBlockWidth];
};

HWY_INLINE uint32_t MaskBits(D d, M m) {
    uint8_t bytes[8] = {};
    hn::StoreMaskBits(d, m, bytes);
    return bytes[0];
}

HWY_INLINE V Abs3Max(V a, V b, V c) {
    // max_component(abs(Vec3{a, b, c}))
    return hn::Max(hn::Max(hn::Abs(a), hn::Abs(b)), hn::Abs(c));
}

// ---- the three primitive tests, one lane per (ray, primitive) pair ----------------------
// Each is written once over vectors: a single ray against a block of primitives passes the
// ray's values broadcast and the primitives' in lanes; a packet of rays against one primitive
// passes the rays in lanes and the primitive broadcast. Either way, each lane computes what
// the scalar test of intersect.cpp computes for its pair.

// Woop, Benthin and Wald's watertight test (see intersect_triangle). p*[vtx]: the vertices
// relative to the ray origin, permuted so that the ray's major axis is z; s*: the shear.
HWY_INLINE M TriangleLanes(D d,
                           V px[3],
                           V py[3],
                           V pz[3],
                           V sx,
                           V sy,
                           V sz,
                           V tmin,
                           V tmax,
                           M active,
                           V* t_out,
                           V* u_out,
                           V* v_out) {
    for (int vtx = 0; vtx < 3; ++vtx) {
        px[vtx] = hn::Add(px[vtx], hn::Mul(sx, pz[vtx]));
        py[vtx] = hn::Add(py[vtx], hn::Mul(sy, pz[vtx]));
    }
    V e0 = hn::Sub(hn::Mul(px[1], py[2]), hn::Mul(py[1], px[2]));
    V e1 = hn::Sub(hn::Mul(px[2], py[0]), hn::Mul(py[2], px[0]));
    V e2 = hn::Sub(hn::Mul(px[0], py[1]), hn::Mul(py[0], px[1]));
    const V zero = hn::Zero(d);
    const M any_zero =
        hn::And(active, hn::Or(hn::Or(hn::Eq(e0, zero), hn::Eq(e1, zero)), hn::Eq(e2, zero)));
    if (HWY_UNLIKELY(!hn::AllFalse(d, any_zero))) {
        // An edge function of exactly 0 is ambiguous in float; such lanes recompute all
        // three in double, where the products of floats are exact (Woop et al. §3.3).
        HWY_ALIGN float x[3][kLeafBlockWidth], y[3][kLeafBlockWidth], e[3][kLeafBlockWidth];
        for (int vtx = 0; vtx < 3; ++vtx) {
            hn::Store(px[vtx], d, x[vtx]);
            hn::Store(py[vtx], d, y[vtx]);
        }
        hn::Store(e0, d, e[0]);
        hn::Store(e1, d, e[1]);
        hn::Store(e2, d, e[2]);
        const uint32_t zero_bits = MaskBits(d, any_zero);
        for (size_t l = 0; l < hn::Lanes(d); ++l) {
            if (!(zero_bits >> l & 1)) continue;
            e[0][l] = static_cast<float>(double(x[1][l]) * y[2][l] - double(y[1][l]) * x[2][l]);
            e[1][l] = static_cast<float>(double(x[2][l]) * y[0][l] - double(y[2][l]) * x[0][l]);
            e[2][l] = static_cast<float>(double(x[0][l]) * y[1][l] - double(y[0][l]) * x[1][l]);
        }
        e0 = hn::Load(d, e[0]);
        e1 = hn::Load(d, e[1]);
        e2 = hn::Load(d, e[2]);
    }
    const M some_neg = hn::Or(hn::Or(hn::Lt(e0, zero), hn::Lt(e1, zero)), hn::Lt(e2, zero));
    const M some_pos = hn::Or(hn::Or(hn::Gt(e0, zero), hn::Gt(e1, zero)), hn::Gt(e2, zero));
    const V det = hn::Add(hn::Add(e0, e1), e2);
    M ok = hn::AndNot(hn::And(some_neg, some_pos), active);
    ok = hn::And(ok, hn::Ne(det, zero));
    if (hn::AllFalse(d, ok)) return ok;

    for (int vtx = 0; vtx < 3; ++vtx) pz[vtx] = hn::Mul(pz[vtx], sz);
    const V t_scaled = hn::Add(hn::Add(hn::Mul(e0, pz[0]), hn::Mul(e1, pz[1])), hn::Mul(e2, pz[2]));
    const V tmin_det = hn::Mul(tmin, det);
    const V tmax_det = hn::Mul(tmax, det);
    const M neg_det = hn::Lt(det, zero), pos_det = hn::Gt(det, zero);
    const M out_neg =
        hn::And(neg_det, hn::Or(hn::Gt(t_scaled, tmin_det), hn::Lt(t_scaled, tmax_det)));
    const M out_pos =
        hn::And(pos_det, hn::Or(hn::Lt(t_scaled, tmin_det), hn::Gt(t_scaled, tmax_det)));
    ok = hn::AndNot(hn::Or(out_neg, out_pos), ok);
    if (hn::AllFalse(d, ok)) return ok;

    const V inv_det = hn::Div(hn::Set(d, 1.0f), det);
    const V t = hn::Mul(t_scaled, inv_det);
    // Reject t that may be <= 0 given the rounding error above (pbrt-v4, §6.8.7).
    const V max_zt = Abs3Max(pz[0], pz[1], pz[2]);
    const V max_xt = Abs3Max(px[0], px[1], px[2]);
    const V max_yt = Abs3Max(py[0], py[1], py[2]);
    const V g2 = hn::Set(d, gamma(2)), g3 = hn::Set(d, gamma(3)), g5 = hn::Set(d, gamma(5));
    const V delta_z = hn::Mul(g3, max_zt);
    const V delta_x = hn::Mul(g5, hn::Add(max_xt, max_zt));
    const V delta_y = hn::Mul(g5, hn::Add(max_yt, max_zt));
    const V delta_e =
        hn::Mul(hn::Set(d, 2.0f),
                hn::Add(hn::Add(hn::Mul(hn::Mul(g2, max_xt), max_yt), hn::Mul(delta_y, max_xt)),
                        hn::Mul(delta_x, max_yt)));
    const V max_e = Abs3Max(e0, e1, e2);
    const V delta_t = hn::Mul(
        hn::Mul(hn::Set(d, 3.0f),
                hn::Add(hn::Add(hn::Mul(hn::Mul(g3, max_e), max_zt), hn::Mul(delta_e, max_zt)),
                        hn::Mul(delta_z, max_e))),
        hn::Abs(inv_det));
    *t_out = t;
    *u_out = hn::Mul(e1, inv_det);
    *v_out = hn::Mul(e2, inv_det);
    return hn::And(ok, hn::Gt(t, delta_t));
}

// The quad test of Ray Tracing: The Next Week (see intersect_quad), with n = cross(u, v) and w = n / dot(n, n)
// precomputed by the same float operations.
struct QuadLanesIn {
    V qx, qy, qz, ux, uy, uz, vx, vy, vz, nx, ny, nz, wx, wy, wz;
};
HWY_INLINE M QuadLanes(D d,
                       const QuadLanesIn& p,
                       V ox,
                       V oy,
                       V oz,
                       V dx,
                       V dy,
                       V dz,
                       V tmin,
                       V tmax,
                       M active,
                       V* t_out,
                       V* u_out,
                       V* v_out) {
    const V zero = hn::Zero(d), one = hn::Set(d, 1.0f);
    const V denom = hn::Add(hn::Add(hn::Mul(p.nx, dx), hn::Mul(p.ny, dy)), hn::Mul(p.nz, dz));
    const V num =
        hn::Add(hn::Add(hn::Mul(p.nx, hn::Sub(p.qx, ox)), hn::Mul(p.ny, hn::Sub(p.qy, oy))),
                hn::Mul(p.nz, hn::Sub(p.qz, oz)));
    const V t = hn::Div(num, denom);
    M ok = hn::And(active, hn::Ne(denom, zero));
    ok = hn::And(ok, hn::And(hn::Ge(t, tmin), hn::Le(t, tmax)));
    if (hn::AllFalse(d, ok)) return ok;
    // p = ray.at(t) - q, then alpha = w . (p x v), beta = w . (u x p).
    const V px = hn::Sub(hn::Add(ox, hn::Mul(t, dx)), p.qx);
    const V py = hn::Sub(hn::Add(oy, hn::Mul(t, dy)), p.qy);
    const V pz = hn::Sub(hn::Add(oz, hn::Mul(t, dz)), p.qz);
    const V pv_x = hn::Sub(hn::Mul(py, p.vz), hn::Mul(pz, p.vy));
    const V pv_y = hn::Sub(hn::Mul(pz, p.vx), hn::Mul(px, p.vz));
    const V pv_z = hn::Sub(hn::Mul(px, p.vy), hn::Mul(py, p.vx));
    const V up_x = hn::Sub(hn::Mul(p.uy, pz), hn::Mul(p.uz, py));
    const V up_y = hn::Sub(hn::Mul(p.uz, px), hn::Mul(p.ux, pz));
    const V up_z = hn::Sub(hn::Mul(p.ux, py), hn::Mul(p.uy, px));
    const V alpha = hn::Add(hn::Add(hn::Mul(p.wx, pv_x), hn::Mul(p.wy, pv_y)), hn::Mul(p.wz, pv_z));
    const V beta = hn::Add(hn::Add(hn::Mul(p.wx, up_x), hn::Mul(p.wy, up_y)), hn::Mul(p.wz, up_z));
    *t_out = t;
    *u_out = alpha;
    *v_out = beta;
    return hn::And(ok, hn::And(hn::And(hn::Ge(alpha, zero), hn::Le(alpha, one)),
                               hn::And(hn::Ge(beta, zero), hn::Le(beta, one))));
}

// The cancellation-free sphere test (see intersect_sphere); a = dot(d, d).
HWY_INLINE M SphereLanes(D d,
                         V cx,
                         V cy,
                         V cz,
                         V radius,
                         V ox,
                         V oy,
                         V oz,
                         V dx,
                         V dy,
                         V dz,
                         V a,
                         V tmin,
                         V tmax,
                         M active,
                         V* t_out) {
    const V zero = hn::Zero(d);
    const V fx = hn::Sub(ox, cx), fy = hn::Sub(oy, cy), fz = hn::Sub(oz, cz);
    const V r2 = hn::Mul(radius, radius);
    const V b = hn::Add(hn::Add(hn::Mul(fx, dx), hn::Mul(fy, dy)), hn::Mul(fz, dz));
    const V c = hn::Sub(hn::Add(hn::Add(hn::Mul(fx, fx), hn::Mul(fy, fy)), hn::Mul(fz, fz)), r2);
    const V s = hn::Div(b, a);
    const V lx = hn::Sub(fx, hn::Mul(dx, s));
    const V ly = hn::Sub(fy, hn::Mul(dy, s));
    const V lz = hn::Sub(fz, hn::Mul(dz, s));
    const V ll = hn::Add(hn::Add(hn::Mul(lx, lx), hn::Mul(ly, ly)), hn::Mul(lz, lz));
    const V disc = hn::Mul(a, hn::Sub(r2, ll));
    M ok = hn::And(active, hn::Not(hn::Lt(disc, zero)));
    if (hn::AllFalse(d, ok)) return ok;
    const V q = hn::Neg(hn::Add(b, hn::CopySign(hn::Sqrt(hn::Max(disc, zero)), b)));
    const M q_zero = hn::Eq(q, zero);
    // Lanes with q = 0 divide by 1 instead and take t0 = 0, as the scalar test does.
    const V t0 =
        hn::IfThenZeroElse(q_zero, hn::Div(c, hn::IfThenElse(q_zero, hn::Set(d, 1.0f), q)));
    const V t1 = hn::Div(q, a);
    const V lo = hn::Min(t0, t1), hi = hn::Max(t0, t1);
    const M lo_in = hn::And(hn::Ge(lo, tmin), hn::Le(lo, tmax));
    const M hi_in = hn::And(hn::Ge(hi, tmin), hn::Le(hi, tmax));
    *t_out = hn::IfThenElse(lo_in, lo, hi);
    return hn::And(ok, hn::Or(lo_in, hi_in));
}

// ---- a single ray against a leaf block ---------------------------------------------------

HWY_INLINE void StoreHits(D d, size_t i, M ok, V t, V u, V v, BlockHits* out) {
    hn::Store(t, d, out->t + i);
    hn::Store(u, d, out->u + i);
    hn::Store(v, d, out->v + i);
    out->bits |= MaskBits(d, ok) << i;
}

HWY_INLINE void TriangleTest(
    const TriangleBlock& b, uint32_t count, const RayLanes& r, float tmax, BlockHits* out) {
    const D d;
    const TriangleRay& tr = r.tri;
    const int k[3] = {tr.kx, tr.ky, tr.kz};
    out->bits = 0;
    for (size_t i = 0; i < size_t(kLeafBlockWidth) && i < count; i += hn::Lanes(d)) {
        V px[3], py[3], pz[3];
        for (int vtx = 0; vtx < 3; ++vtx) {
            px[vtx] = hn::Sub(hn::Load(d, b.p[vtx][k[0]] + i), hn::Set(d, tr.o[k[0]]));
            py[vtx] = hn::Sub(hn::Load(d, b.p[vtx][k[1]] + i), hn::Set(d, tr.o[k[1]]));
            pz[vtx] = hn::Sub(hn::Load(d, b.p[vtx][k[2]] + i), hn::Set(d, tr.o[k[2]]));
        }
        V t = hn::Zero(d), u = t, v = t;
        const M ok = TriangleLanes(d, px, py, pz, hn::Set(d, tr.sx), hn::Set(d, tr.sy),
                                   hn::Set(d, tr.sz), hn::Set(d, r.ray.tmin), hn::Set(d, tmax),
                                   hn::FirstN(d, count - i), &t, &u, &v);
        StoreHits(d, i, ok, t, u, v, out);
    }
}

HWY_INLINE void QuadTest(
    const QuadBlock& b, uint32_t count, const RayLanes& r, float tmax, BlockHits* out) {
    const D d;
    const Ray& ray = r.ray;
    out->bits = 0;
    for (size_t i = 0; i < size_t(kLeafBlockWidth) && i < count; i += hn::Lanes(d)) {
        const QuadLanesIn p{
            hn::Load(d, b.q[0] + i), hn::Load(d, b.q[1] + i), hn::Load(d, b.q[2] + i),
            hn::Load(d, b.u[0] + i), hn::Load(d, b.u[1] + i), hn::Load(d, b.u[2] + i),
            hn::Load(d, b.v[0] + i), hn::Load(d, b.v[1] + i), hn::Load(d, b.v[2] + i),
            hn::Load(d, b.n[0] + i), hn::Load(d, b.n[1] + i), hn::Load(d, b.n[2] + i),
            hn::Load(d, b.w[0] + i), hn::Load(d, b.w[1] + i), hn::Load(d, b.w[2] + i)};
        V t = hn::Zero(d), u = t, v = t;
        const M ok =
            QuadLanes(d, p, hn::Set(d, ray.o.x), hn::Set(d, ray.o.y), hn::Set(d, ray.o.z),
                      hn::Set(d, ray.d.x), hn::Set(d, ray.d.y), hn::Set(d, ray.d.z),
                      hn::Set(d, ray.tmin), hn::Set(d, tmax), hn::FirstN(d, count - i), &t, &u, &v);
        StoreHits(d, i, ok, t, u, v, out);
    }
}

HWY_INLINE void SphereTest(
    const SphereBlock& b, uint32_t count, const RayLanes& r, float tmax, BlockHits* out) {
    const D d;
    const Ray& ray = r.ray;
    out->bits = 0;
    for (size_t i = 0; i < size_t(kLeafBlockWidth) && i < count; i += hn::Lanes(d)) {
        V t = hn::Zero(d);
        const M ok =
            SphereLanes(d, hn::Load(d, b.c[0] + i), hn::Load(d, b.c[1] + i),
                        hn::Load(d, b.c[2] + i), hn::Load(d, b.r + i), hn::Set(d, ray.o.x),
                        hn::Set(d, ray.o.y), hn::Set(d, ray.o.z), hn::Set(d, ray.d.x),
                        hn::Set(d, ray.d.y), hn::Set(d, ray.d.z), hn::Set(d, dot(ray.d, ray.d)),
                        hn::Set(d, ray.tmin), hn::Set(d, tmax), hn::FirstN(d, count - i), &t);
        StoreHits(d, i, ok, t, hn::Zero(d), hn::Zero(d), out);
    }
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_ACCEL_WIDE_LEAF_TESTS_INL_H_
