// The point and normals of a hit on a quad, a triangle or a sphere: what surface_at computes for
// such hits (the rest of a SurfaceHit, uv and material, stays there), written once over lanes.
// surface_at runs the one-lane instance for both engines; the wavefront's shade kernel runs it
// over the Lambertian and metal hits of a chunk (blocks/lane_kernels.cpp), so that
// their vertices never go through the scalar code. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_SCENE_SURFACE_POINT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_SCENE_SURFACE_POINT_INL_H_
#undef WAVETRACE_SCENE_SURFACE_POINT_INL_H_
#else
#define WAVETRACE_SCENE_SURFACE_POINT_INL_H_
#endif

#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

template <class L>
struct SurfacePoint {
    V3<typename L::F> p;   // on the surface
    V3<typename L::F> ng;  // geometric normal, unit, on the shape's front
    V3<typename L::F> ns;  // shading normal, unit, on ng's side
};

// The quad q + a eu + b ev at the hit's (a, b); its normal is along eu x ev.
template <class L>
HWY_INLINE SurfacePoint<L> QuadPoint(V3<typename L::F> q,
                                     V3<typename L::F> eu,
                                     V3<typename L::F> ev,
                                     typename L::F a,
                                     typename L::F b) {
    SurfacePoint<L> s;
    s.p = q + eu * a + ev * b;
    s.ng = s.ns = Normalize<L>(Cross(eu, ev));
    return s;
}

// The sphere of centre c and radius r at its point p (the hit, o + t d): the outward normal.
template <class L>
HWY_INLINE SurfacePoint<L> SpherePoint(V3<typename L::F> p, V3<typename L::F> c, typename L::F r) {
    SurfacePoint<L> s;
    s.p = p;
    s.ng = s.ns = Normalize<L>((p - c) * (L::Set(1.0f) / r));
    return s;
}

// The triangle (p0, p1, p2) at barycentrics (1 - b1 - b2, b1, b2): the position interpolated
// from the vertices (more accurate than o + t d), the normal along (p1 - p0) x (p2 - p0), and
// where the mesh has vertex normals (`smooth`), their interpolation, unless it vanishes. The
// shading normal is turned to ng's side, as interpolation can flip it.
template <class L>
HWY_INLINE SurfacePoint<L> TrianglePoint(const V3<typename L::F> (&p)[3],
                                         const V3<typename L::F> (&n)[3],
                                         typename L::M smooth,
                                         typename L::F b1,
                                         typename L::F b2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    const F b0 = L::Set(1.0f) - b1 - b2;
    SurfacePoint<L> s;
    s.p = p[0] * b0 + p[1] * b1 + p[2] * b2;
    s.ng = Normalize<L>(Cross(p[1] - p[0], p[2] - p[0]));
    const V3<F> ni = n[0] * b0 + n[1] * b1 + n[2] * b2;
    const auto use = L::And(smooth, Dot(ni, ni) > zero);
    const V3<F> ns = Normalize<L>(ni);
    s.ns = Select3<L>(use, ns, s.ng);
    const auto flip = Dot(s.ns, s.ng) < zero;
    s.ns = Select3<L>(flip, Neg3<L>(s.ns), s.ns);
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_SCENE_SURFACE_POINT_INL_H_
