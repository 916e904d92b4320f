// Environment maps written once over lanes: the mapping between directions and the image's
// (u, v), and the radiance looked up there (bilinear for latitude-longitude maps, the texel
// for equal-area ones). eval_background and LightSet run the one-lane instances, the
// wavefront's kernels the same formulas in SIMD lanes, with gathers for the texels. Per-target
// header, see math/lanes-inl.h.
#if defined(WAVETRACE_SCENE_ENVIRONMENT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SCENE_ENVIRONMENT_INL_H_
#undef WAVETRACE_SCENE_ENVIRONMENT_INL_H_
#else
#define WAVETRACE_SCENE_ENVIRONMENT_INL_H_
#endif

#include "math/equal_area-inl.h"
#include "math/lanes-inl.h"
#include "scene/environment_view.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// x where it is finite, else 0: the formulas below turn (u, v) into table indices.
template <class L>
HWY_INLINE typename L::F FiniteOrZero(typename L::F x) {
    return L::Select(L::IsFinite(x), x, L::Set(0.0f));
}

// The map's axes as lanes: row r of EnvironmentView::frame.
template <class L>
HWY_INLINE V3<typename L::F> FrameAxis(const EnvironmentView& e, int r) {
    return {L::Set(e.frame[r][0]), L::Set(e.frame[r][1]), L::Set(e.frame[r][2])};
}

// The solid angle per unit area of (u, v) at row v: 2 pi^2 sin(pi v) for a lat-long map,
// 4 pi for an equal-area one.
template <class L>
HWY_INLINE typename L::F EnvironmentJacobian(const EnvironmentView& e, typename L::F v) {
    if (e.equal_area) return L::Set(4.0f * kPi);
    typename L::F sin_theta, cos_theta;
    SinCos2Pi<L>(v * L::Set(0.5f), &sin_theta, &cos_theta);
    return L::Set(2.0f * kPi * kPi) * sin_theta;
}

// The unit world direction w to the map's (u, v) in [0, 1)^2, v = 0 at the top row. Lat-long:
// phi = atan2(x, -z) about the map's +y, less the rotation, u = 1/2 + phi / 2 pi, and
// v = theta / pi from +y.
template <class L>
HWY_INLINE void EnvironmentUv(const EnvironmentView& e,
                              V3<typename L::F> w,
                              typename L::F* u,
                              typename L::F* v) {
    using F = typename L::F;
    const F below_one = L::Set(0x1.fffffep-1f);
    if (e.framed)
        w = {Dot(w, FrameAxis<L>(e, 0)), Dot(w, FrameAxis<L>(e, 1)), Dot(w, FrameAxis<L>(e, 2))};
    if (e.equal_area) {
        EqualAreaSphereToSquare<L>(w, u, v);
        // [0, 1) as the other mapping: the square's far edges are its texels' inner borders.
        *u = L::Min(*u, below_one);
        *v = L::Min(*v, below_one);
        return;
    }
    const F one = L::Set(1.0f);
    const F phi = Atan2<L>(w.x, L::Neg(w.z));
    const F turns = L::Set(0.5f) + phi * L::Set(0.5f * kInvPi) - L::Set(e.rotation);
    *u = L::Min(turns - L::Floor(turns), below_one);
    *v = Acos<L>(L::Min(L::Max(w.y, L::Neg(one)), one)) * L::Set(kInvPi);
}

// The unit world direction at the map's (u, v) in [0, 1]^2, and the Jacobian there
// (EnvironmentJacobian).
template <class L>
HWY_INLINE V3<typename L::F> EnvironmentDirection(const EnvironmentView& e,
                                                  typename L::F u,
                                                  typename L::F v,
                                                  typename L::F* jacobian) {
    using F = typename L::F;
    V3<F> w;
    if (e.equal_area) {
        w = EqualAreaSquareToSphere<L>(u, v);
        *jacobian = L::Set(4.0f * kPi);
    } else {
        F turns = u - L::Set(0.5f) + L::Set(e.rotation);
        turns = turns - L::Floor(turns);
        F sin_phi, cos_phi, sin_theta, cos_theta;
        SinCos2Pi<L>(turns, &sin_phi, &cos_phi);
        SinCos2Pi<L>(v * L::Set(0.5f), &sin_theta, &cos_theta);
        w = {sin_theta * sin_phi, cos_theta, L::Neg(sin_theta) * cos_phi};
        *jacobian = L::Set(2.0f * kPi * kPi) * sin_theta;
    }
    if (!e.framed) return w;
    return FrameAxis<L>(e, 0) * w.x + FrameAxis<L>(e, 1) * w.y + FrameAxis<L>(e, 2) * w.z;
}

// Texel (x, y)'s first float, and its RGB, gathered.
template <class L>
HWY_INLINE typename L::I TexelIndex(const EnvironmentView& e, typename L::I x, typename L::I y) {
    return L::MulI(L::AddI(L::MulI(y, L::SetI(e.width)), x), L::SetI(3));
}
template <class L>
HWY_INLINE V3<typename L::F> Texel(const EnvironmentView& e, typename L::I x, typename L::I y) {
    const typename L::I i = TexelIndex<L>(e, x, y);
    return {L::Gather(e.texels, i), L::Gather(e.texels, L::AddI(i, L::SetI(1))),
            L::Gather(e.texels, L::AddI(i, L::SetI(2)))};
}

// The map's (u, v) that a ray of direction d, of any length, leaves the scene towards: what
// both engines look up for an escaped ray.
template <class L>
HWY_INLINE void EnvironmentUvOfRay(const EnvironmentView& e,
                                   V3<typename L::F> d,
                                   typename L::F* u,
                                   typename L::F* v) {
    EnvironmentUv<L>(e, Normalize<L>(d), u, v);
}

// The texels the radiance at the map's (u, v) is read from, v = 0 at the top, and their
// weights. Lat-long: bilinear between texel centres at half-integer coordinates, wrapping in u
// and clamped in v (the top and bottom rows are the poles, not neighbours); with rows_at_poles
// row j sits at v = j / (H - 1) instead of (j + 1/2) / H. Equal-area: the texel (u, v) falls in
// (x0 = x1, y0 = y1, weights 0).
template <class L>
struct EnvironmentTaps {
    typename L::I x0, x1, y0, y1;
    typename L::F tx, ty;  // the weights of x1 and of y1
};
template <class L>
HWY_INLINE EnvironmentTaps<L> EnvironmentTapsAt(const EnvironmentView& e,
                                                typename L::F u,
                                                typename L::F v) {
    using F = typename L::F;
    using I = typename L::I;
    const F zero = L::Set(0.0f), one = L::Set(1.0f), half = L::Set(0.5f);
    const F w = L::Set(static_cast<float>(e.width)), h = L::Set(static_cast<float>(e.height));
    const I last_x = L::SetI(e.width - 1), last_y = L::SetI(e.height - 1);
    u = FiniteOrZero<L>(u);
    v = FiniteOrZero<L>(v);
    if (e.equal_area) {
        const I x = L::MinI(L::Trunc(L::Min(L::Max(u, zero), one) * w), last_x);
        const I y = L::MinI(L::Trunc(L::Min(L::Max(v, zero), one) * h), last_y);
        return {x, x, y, y, zero, zero};
    }
    if (e.rows_at_poles) v = (v * (h - one) + half) / h;
    const F x = (u - L::Floor(u)) * w - half;  // in [-1/2, W - 1/2]
    const F y = L::Min(L::Max(v * h - half, zero), h - one);
    const F fx = L::Floor(x), fy = L::Floor(y);
    // Columns -1 and W wrap to W - 1 and 0.
    const I x0 = L::Trunc(L::Select(fx < zero, w - one, fx));
    const I x1 = L::Trunc(L::Select(fx + one < w, fx + one, zero));
    const I y0 = L::Trunc(fy), y1 = L::MinI(L::AddI(y0, L::SetI(1)), last_y);
    return {x0, x1, y0, y1, x - fx, y - fy};
}

// The radiance at the map's (u, v) (EnvironmentTapsAt).
template <class L>
HWY_INLINE V3<typename L::F> EnvironmentRadiance(const EnvironmentView& e,
                                                 typename L::F u,
                                                 typename L::F v) {
    using F = typename L::F;
    const F one = L::Set(1.0f);
    const V3<F> scale{L::Set(e.scale[0]), L::Set(e.scale[1]), L::Set(e.scale[2])};
    const EnvironmentTaps<L> k = EnvironmentTapsAt<L>(e, u, v);
    if (e.equal_area) return Texel<L>(e, k.x0, k.y0) * scale;
    const V3<F> top = Texel<L>(e, k.x0, k.y0) * (one - k.tx) + Texel<L>(e, k.x1, k.y0) * k.tx;
    const V3<F> bottom = Texel<L>(e, k.x0, k.y1) * (one - k.tx) + Texel<L>(e, k.x1, k.y1) * k.tx;
    return (top * (one - k.ty) + bottom * k.ty) * scale;
}

// For a caller that looks up many (u, v) after this: their texels fetched ahead.
template <class L>
HWY_INLINE void PrefetchEnvironmentTexels(const EnvironmentView& e,
                                          typename L::F u,
                                          typename L::F v) {
    const EnvironmentTaps<L> k = EnvironmentTapsAt<L>(e, u, v);
    const auto at = [&](typename L::I x, typename L::I y) { return TexelIndex<L>(e, x, y); };
    L::Prefetch(e.texels, at(k.x0, k.y0));
    L::Prefetch(e.texels, at(k.x0, k.y1));
    if (e.equal_area) return;
    L::Prefetch(e.texels, L::AddI(at(k.x1, k.y0), L::SetI(2)));
    L::Prefetch(e.texels, L::AddI(at(k.x1, k.y1), L::SetI(2)));
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SCENE_ENVIRONMENT_INL_H_
