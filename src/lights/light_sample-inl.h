// A light sample at a Lambertian or a glossy surface vertex (glossy-inl.h), or a vertex in a
// medium of isotropic phase function, towards a quad or triangle light of constant radiance
// (the light point, uniform by area, and its solid-angle density), a point or directional
// light, or a point sphere_light-inl.h or environment_light-inl.h found: the BSDF value and
// density and the shadow ray; what next_event computes for such a vertex and light, once.
// Unweighted: the MIS weight is the caller's (the megakernel's loop, the wavefront's
// mis_combine). The megakernel runs it with OneLane inside next_event; the wavefront's
// light_sample kernel runs it over the queued vertices whose sample picked such a light
// (blocks/lane_kernels.cpp). Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_LIGHTS_LIGHT_SAMPLE_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_LIGHTS_LIGHT_SAMPLE_INL_H_
#undef WAVETRACE_LIGHTS_LIGHT_SAMPLE_INL_H_
#else
#define WAVETRACE_LIGHTS_LIGHT_SAMPLE_INL_H_
#endif

#include "bsdfs/diffuse-inl.h"
#include "bsdfs/geometric_side-inl.h"
#include "bsdfs/glossy-inl.h"
#include "lights/light_columns.h"
#include "math/lanes-inl.h"
#include "sampling/warp-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// A quad or triangle light of LightSet::planar_emitter_columns(), in lanes (each lane's own
// light).
template <class L>
struct PlanarLightLanes {
    // corner and edges: the points q + s u + t v, s and t in [0, 1) (a quad) or s, t >= 0 and
    // s + t <= 1 (a triangle)
    V3<typename L::F> q, u, v;
    V3<typename L::F> n;  // unit normal, cross(u, v) normalized: the front side
    typename L::F area;
    V3<typename L::F> radiance;  // emitted from the front (and the back if two-sided)
    typename L::M two_sided;
    typename L::M triangle;
    typename L::F select_prob;  // of picking this light
};

// Three columns (x, y, z) read through fetch.
template <class L, class Fetch>
HWY_INLINE V3<typename L::F> Fetch3(Fetch fetch, const std::vector<float>* columns) {
    return {fetch(columns[0]), fetch(columns[1]), fetch(columns[2])};
}

// Each lane's light read from the columns: fetch(column) gives a column's value in each lane
// (one entry in scalar code; a gather or a broadcast over vectors).
template <class L, class Fetch>
HWY_INLINE PlanarLightLanes<L> PlanarLightFrom(const PlanarEmitterColumns& c,
                                               Fetch fetch,
                                               typename L::F select_prob) {
    return {Fetch3<L>(fetch, c.q),
            Fetch3<L>(fetch, c.u),
            Fetch3<L>(fetch, c.v),
            Fetch3<L>(fetch, c.n),
            fetch(c.area),
            Fetch3<L>(fetch, c.radiance),
            fetch(c.two_sided) > L::Set(0.0f),
            fetch(c.triangle) > L::Set(0.0f),
            select_prob};
}

// The vertex a light sample starts from.
template <class L>
struct LightSampleVertex {
    V3<typename L::F> p, ng, ns, wo;
    LaneBsdf<L> bsdf;
    typename L::F u1, u2;             // the point on the light
    bool geometric_side_test = true;  // Scene::geometric_side_test
};

// The light sample seen from the vertex: what it contributes and the shadow ray that tests it.
template <class L>
struct VertexLightSample {
    typename L::M valid;      // false: no contribution (back face, below the surface ...)
    V3<typename L::F> value;  // f |cos| Le / p_light: unweighted, unoccluded
    typename L::F pdf_light, pdf_bsdf;
    V3<typename L::F> origin, wi;  // the shadow ray (ShadowRayTo), t in [0, tmax]
    typename L::F tmax;
};

// Where a shadow ray towards a light point at distance dist ends: 1e-4 relative short of it, so
// that the ray does not find the light itself (a point at infinity stays there).
template <class L>
HWY_INLINE typename L::F ShadowRayEnd(typename L::F dist) {
    return dist * L::Set(1.0f - 1e-4f);
}

// The shadow ray from p (geometric normal ng) towards a light point at unit direction wi and
// distance dist: from p's offset origin (OffsetRayOrigin), aimed at the point itself and ending
// ShadowRayEnd short of it. Aimed along wi from the offset origin, the ray would be displaced by
// the offset, which carries it across a light seen at a grazing angle before its end. A point at
// infinity (dist infinite) keeps wi.
template <class L>
HWY_INLINE void ShadowRayTo(V3<typename L::F> p,
                            V3<typename L::F> ng,
                            V3<typename L::F> wi,
                            typename L::F dist,
                            V3<typename L::F>* origin,
                            V3<typename L::F>* dir,
                            typename L::F* tmax) {
    using F = typename L::F;
    *origin = OffsetRayOrigin<L>(p, ng, wi);
    const auto finite = L::IsFinite(dist);
    const V3<F> to = p + wi * L::Select(finite, dist, L::Set(0.0f)) - *origin;
    const F len = L::Sqrt(Dot(to, to));
    const auto aimed = L::And(finite, len > L::Set(0.0f));
    *dir = Select3<L>(aimed, to * (L::Set(1.0f) / len), wi);
    *tmax = L::Select(aimed, ShadowRayEnd<L>(len), ShadowRayEnd<L>(dist));
}

// A point sampled on a light, seen from the vertex: the unit direction to it and its distance,
// the density of that direction (times the light's selection probability) and the radiance
// arriving (zero from a back face), valid where all of that is usable.
template <class L>
struct LightPoint {
    typename L::M valid;
    V3<typename L::F> wi;
    typename L::F dist, pdf;
    V3<typename L::F> radiance;
};

template <class L>
HWY_INLINE LightPoint<L> SelectLightPoint(typename L::M m,
                                          const LightPoint<L>& a,
                                          const LightPoint<L>& b) {
    return {L::Or(L::And(m, a.valid), L::AndNot(m, b.valid)), Select3<L>(m, a.wi, b.wi),
            L::Select(m, a.dist, b.dist), L::Select(m, a.pdf, b.pdf),
            Select3<L>(m, a.radiance, b.radiance)};
}

// The light's point, uniform by area: p_w = r^2 / (|cos theta_l| A), times the selection
// probability. On a triangle, (s, t) = (sqrt(u1) (1 - u2), sqrt(u1) u2), as
// sample_uniform_triangle (sampling/warp.h) warps the square.
template <class L>
HWY_INLINE LightPoint<L> PlanarLightPoint(V3<typename L::F> ref,
                                          const PlanarLightLanes<L>& e,
                                          typename L::F u1,
                                          typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    LightPoint<L> r;
    F s = u1, t = u2;
    if (L::Any(e.triangle)) {
        const F root = L::Sqrt(u1);
        s = L::Select(e.triangle, root * (one - u2), s);
        t = L::Select(e.triangle, root * u2, t);
    }
    const V3<F> x = e.q + e.u * s + e.v * t;
    const V3<F> d = x - ref;
    const F dist2 = Dot(d, d);
    r.dist = L::Sqrt(dist2);
    r.wi = d * (one / r.dist);
    const F cos_l = L::Abs(Dot(e.n, r.wi));
    r.pdf = UniformAreaToSolidAngle<L>(dist2, cos_l, e.area) * e.select_prob;
    const auto emits = L::Or(Dot(d, e.n) < zero, e.two_sided);
    r.radiance = Select3<L>(emits, e.radiance, V3<F>{zero, zero, zero});
    r.valid = L::And(L::And(dist2 > zero, cos_l > zero), L::And(L::IsFinite(r.pdf), r.pdf > zero));
    r.valid = L::And(r.valid, MaxComponent<L>(r.radiance) > zero);
    return r;
}

// A point or directional light of LightSet::delta_light_columns(), in lanes (each lane's own).
template <class L>
struct DeltaLightLanes {
    V3<typename L::F> at;         // a point light's position; a directional light's -direction
    V3<typename L::F> intensity;  // radiant intensity; a directional light's irradiance
    typename L::M directional;
    typename L::F select_prob;  // of picking this light
};

template <class L, class Fetch>
HWY_INLINE DeltaLightLanes<L> DeltaLightFrom(const DeltaLightColumns& c,
                                             Fetch fetch,
                                             typename L::F select_prob) {
    return {Fetch3<L>(fetch, c.at), Fetch3<L>(fetch, c.intensity),
            fetch(c.directional) > L::Set(0.0f), select_prob};
}

// The light's one point: a point light at distance r along wi, arriving as I / r^2; a
// directional light at infinity along -direction, arriving as its irradiance. A delta in
// direction: the density is the selection probability (no BSDF sample finds the light: the
// caller sets the BSDF density to 0, for an MIS weight of 1).
template <class L>
HWY_INLINE LightPoint<L> DeltaLightPoint(V3<typename L::F> ref, const DeltaLightLanes<L>& e) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const V3<F> d = e.at - ref;
    const F dist2 = Dot(d, d);
    const F dist = L::Sqrt(dist2);
    LightPoint<L> r;
    r.wi = Select3<L>(e.directional, e.at, d * (one / dist));
    r.dist = L::Select(e.directional, L::Set(kInfinity), dist);
    r.pdf = e.select_prob;
    r.radiance = Select3<L>(e.directional, e.intensity, e.intensity * (one / dist2));
    const auto placed = L::Or(e.directional, L::And(dist2 > zero, L::IsFinite(dist)));
    r.valid = L::And(L::And(placed, r.pdf > zero), MaxComponent<L>(r.radiance) > zero);
    return r;
}

// The light sample at a vertex towards a light point: the BSDF value and density and the
// shadow ray.
template <class L>
HWY_INLINE VertexLightSample<L> SampleTowards(const LightSampleVertex<L>& v,
                                              const LightPoint<L>& l) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    VertexLightSample<L> r;
    r.wi = l.wi;
    r.pdf_light = l.pdf;
    auto ok = l.valid;
    // The BSDF's f |cos| and density, zero where wi leaves through the geometric surface but not
    // through the shading surface as a transmission (a dielectric's, a metallic-roughness
    // surface's), or the other way round
    // (eval_world; a reflecting lobe is zero through the shading surface); in a medium, the
    // phase function's f = albedo / (4 pi), the density of a uniform direction.
    if (v.geometric_side_test) {
        const auto transmits = L::And(L::Or(v.bsdf.dielectric, v.bsdf.metallic_roughness),
                                      Dot(v.wo, v.ns) * Dot(r.wi, v.ns) < zero);
        ok = L::AndNot(WrongGeometricSide<L>(v.wo, r.wi, v.ng, transmits), ok);
    }
    V3<F> f{zero, zero, zero};
    F pdf_bsdf = zero;
    const auto glossy = v.bsdf.glossy();
    if (L::Any(L::Not(glossy)))
        f = LambertianEval<L>(v.bsdf.albedo, Dot(v.wo, v.ns), Dot(r.wi, v.ns), &pdf_bsdf);
    if (L::Any(glossy)) {
        F pdf_glossy;
        f = Select3<L>(glossy, GlossyEval<L>(v.bsdf, v.ns, v.wo, r.wi, &pdf_glossy), f);
        pdf_bsdf = L::Select(glossy, pdf_glossy, pdf_bsdf);
    }
    if (L::Any(v.bsdf.phase)) {
        F pdf_phase;
        f = Select3<L>(v.bsdf.phase, PhaseEval<L>(v.bsdf.albedo, &pdf_phase), f);
        pdf_bsdf = L::Select(v.bsdf.phase, pdf_phase, pdf_bsdf);
    }
    r.pdf_bsdf = pdf_bsdf;
    ok = L::And(ok, MaxComponent<L>(f) > zero);
    r.valid = ok;
    r.value = f * l.radiance * (one / l.pdf);
    ShadowRayTo<L>(v.p, v.ng, l.wi, l.dist, &r.origin, &r.wi, &r.tmax);
    return r;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_LIGHTS_LIGHT_SAMPLE_INL_H_
