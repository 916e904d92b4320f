// A point sampled on a sphere light seen from outside it: uniform in the cone of directions the
// sphere subtends (pbrt-v4 §6.2.4), then the nearest point of the sphere along that direction;
// with the radiance arriving from it and the density of its direction. Written once over lanes:
// LightSet::sample takes the point (SphereConePoint) for both engines, next_event the whole
// sample at Lambertian and metal vertices (SphereLightPoint), and the wavefront's shade kernel
// runs it a vector of vertices at a time (blocks/lane_kernels.cpp). Per-target header, see
// math/lanes-inl.h.
#if defined(WAVETRACE_LIGHTS_SPHERE_LIGHT_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_LIGHTS_SPHERE_LIGHT_INL_H_
#undef WAVETRACE_LIGHTS_SPHERE_LIGHT_INL_H_
#else
#define WAVETRACE_LIGHTS_SPHERE_LIGHT_INL_H_
#endif

#include "accel/sphere_hit-inl.h"
#include "lights/light_columns.h"
#include "lights/light_sample-inl.h"
#include "math/lanes-inl.h"
#include "scene/surface_point-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// A sphere light of LightSet::sphere_emitter_columns(), in lanes (each lane's own light).
template <class L>
struct SphereLightLanes {
    V3<typename L::F> centre;
    typename L::F radius;
    V3<typename L::F> radiance;  // emitted outwards (and inwards if two-sided)
    typename L::M two_sided;
    typename L::F select_prob;  // of picking this light
};

template <class L, class Fetch>
HWY_INLINE SphereLightLanes<L> SphereLightFrom(const SphereEmitterColumns& c,
                                               Fetch fetch,
                                               typename L::F select_prob) {
    return {Fetch3<L>(fetch, c.centre), fetch(c.radius), Fetch3<L>(fetch, c.radiance),
            fetch(c.two_sided) > L::Set(0.0f), select_prob};
}

// Whether ref lies outside the sphere (with a margin): where the cone sampling applies.
template <class L>
HWY_INLINE typename L::M SphereOutside(V3<typename L::F> ref,
                                       V3<typename L::F> centre,
                                       typename L::F radius) {
    const V3<typename L::F> fc = centre - ref;
    return Dot(fc, fc) > radius * radius * L::Set(1.0001f);
}

// 1 - cos theta_max of the cone the sphere subtends from ref (outside it), as
// s / (1 + sqrt(1 - s)) with s = sin^2 theta_max: without cancellation for the tiny cones of far
// spheres.
template <class L>
HWY_INLINE typename L::F SphereConeOneMinusCos(V3<typename L::F> ref,
                                               V3<typename L::F> centre,
                                               typename L::F radius) {
    const V3<typename L::F> fc = centre - ref;
    const typename L::F sin2 = radius * radius / Dot(fc, fc);
    return sin2 / (L::Set(1.0f) + L::Sqrt(L::Set(1.0f) - sin2));
}

// The point of the sphere sampled from ref (outside it) and the solid-angle density of its
// direction, 1 / (2 pi (1 - cos theta_max)).
template <class L>
HWY_INLINE V3<typename L::F> SphereConePoint(V3<typename L::F> ref,
                                             V3<typename L::F> centre,
                                             typename L::F radius,
                                             typename L::F u1,
                                             typename L::F u2,
                                             typename L::F* pdf_solid) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const V3<F> fc = centre - ref;
    const F one_minus_cos = SphereConeOneMinusCos<L>(ref, centre, radius);
    const V3<F> axis = Normalize<L>(fc);
    const F cos_t = one - u1 * one_minus_cos;
    const F sin_t = L::Sqrt(L::Max(zero, u1 * one_minus_cos * (L::Set(2.0f) - u1 * one_minus_cos)));
    F sin_phi, cos_phi;
    SinCos2Pi<L>(u2, &sin_phi, &cos_phi);
    V3<F> s, t;
    OrthonormalBasis<L>(axis, &s, &t);
    const V3<F> w = s * (sin_t * cos_phi) + t * (sin_t * sin_phi) + axis * cos_t;
    // The nearest point along w; a grazing direction that misses by rounding takes the tangent
    // point.
    F th;
    const auto hits = SphereHit<L>(ref, w, centre, radius, zero, L::Set(kInfinity), &th);
    *pdf_solid = one / (L::Set(2.0f * kPi) * one_minus_cos);
    return ref + w * L::Select(hits, th, Dot(fc, w));
}

// The light point of a sphere light for a vertex at ref outside it, which the callers check
// first (sphere_light_sample_at): as LightSample gives it, the direction, distance, density times
// the selection probability, and the radiance of the sphere's side facing ref.
template <class L>
HWY_INLINE LightPoint<L> SphereLightPoint(V3<typename L::F> ref,
                                          const SphereLightLanes<L>& e,
                                          typename L::F u1,
                                          typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    LightPoint<L> r;
    F pdf_solid;
    const V3<F> x = SphereConePoint<L>(ref, e.centre, e.radius, u1, u2, &pdf_solid);
    const V3<F> d = x - ref;
    const F dist2 = Dot(d, d);
    r.dist = L::Sqrt(dist2);
    r.wi = d * (one / r.dist);
    // The sphere's normal at the point as surface_at gives it for the segment ref -> ref + d.
    const V3<F> ng = SpherePoint<L>(ref + d, e.centre, e.radius).ng;
    const auto emits = L::Or(Dot(d, ng) < zero, e.two_sided);
    r.radiance = Select3<L>(emits, e.radiance, V3<F>{zero, zero, zero});
    r.pdf = pdf_solid * e.select_prob;
    r.valid = L::And(dist2 > zero, L::And(L::IsFinite(r.pdf), r.pdf > zero));
    r.valid = L::And(r.valid, MaxComponent<L>(r.radiance) > zero);
    return r;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_LIGHTS_SPHERE_LIGHT_INL_H_
