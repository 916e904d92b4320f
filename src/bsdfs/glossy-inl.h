// The glossy lobes of lane vertices over lanes: a rough metal (metal-inl.h), a rough conductor
// (conductor-inl.h), a rough dielectric (dielectric-inl.h) or glTF's metallic-roughness with
// rough lobes (metallic_roughness-inl.h), isotropic, each lane of its own, in world directions
// about the shading normal. An isotropic lobe needs no tangent, so the frame is
// OrthonormalBasis(ns) and nothing of the hit's dp/du. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_GLOSSY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_GLOSSY_INL_H_
#undef WAVETRACE_BSDFS_GLOSSY_INL_H_
#else
#define WAVETRACE_BSDFS_GLOSSY_INL_H_
#endif

#include "bsdfs/bsdf.h"
#include "bsdfs/conductor-inl.h"
#include "bsdfs/dielectric-inl.h"
#include "bsdfs/lane_lobe.h"
#include "bsdfs/metal-inl.h"
#include "bsdfs/metallic_roughness-inl.h"
#include "bsdfs/metallic_roughness.h"
#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The BSDF of a lane vertex, each lane's own: its kind by the masks (none set: Lambertian) and
// the parameters each kind reads.
template <class L>
struct LaneBsdf {
    // Lambertian, metal, metallic-roughness, phase function: the colour (a metal's F0, the
    // base colour); conductor: the reflectance factor
    V3<typename L::F> albedo;
    typename L::F alpha;       // the glossy lobes' roughness (> 0)
    // conductor: the complex index of refraction; dielectric: eta.x, the index inside over
    // outside (the shading normal's side)
    V3<typename L::F> eta, k;
    typename L::M beckmann;  // conductor, dielectric: a Beckmann distribution, else GGX
    // metallic-roughness (metallic_roughness-inl.h)
    typename L::F f0, metallic, transmission, clearcoat, coat_alpha;
    typename L::M one_sided;
    // The kind; a delta lane (specular-inl.h) is a smooth metal, conductor or dielectric by
    // these masks, or a mirror where none is set.
    typename L::M metal, conductor, dielectric, metallic_roughness, phase, delta;

    typename L::M glossy() const {
        return L::AndNot(delta,
                         L::Or(L::Or(L::Or(metal, conductor), dielectric), metallic_roughness));
    }
    MicrofacetLanes<L> as_dielectric() const { return {beckmann, alpha, alpha}; }
    RoughConductor<L> as_conductor() const { return {albedo, eta, k, {beckmann, alpha, alpha}}; }
    MetallicRoughnessLanes<L> as_metallic_roughness() const {
        // A lane vertex's coat lies along the shading normal (is_lane_bsdf).
        const typename L::F zero = L::Set(0.0f);
        return {albedo,       alpha,     f0,         metallic,
                transmission, clearcoat, coat_alpha, {zero, zero, L::Set(1.0f)},
                one_sided};
    }
};

// The one-lane view of a lane BSDF b (is_lane_bsdf).
inline LaneBsdf<OneLane> to_lanes(const BsdfParams& b) {
    return {to_lanes(b.albedo),
            b.alpha,
            to_lanes(lane_eta(b)),
            to_lanes(b.conductor_k),
            b.distribution == Microfacet::Beckmann,
            schlick_f0(b.eta),
            b.metallic,
            b.transmission,
            b.clearcoat,
            b.clearcoat_alpha,
            b.one_sided,
            b.kind == MaterialKind::Metal,
            b.kind == MaterialKind::Conductor,
            b.kind == MaterialKind::Dielectric,
            b.kind == MaterialKind::MetallicRoughness,
            b.kind == MaterialKind::Isotropic,
            b.is_delta()};
}

// The shading frame about the unit normal ns, and w in it.
template <class L>
struct GlossyFrame {
    V3<typename L::F> s, t, n;

    explicit GlossyFrame(V3<typename L::F> ns) : n(ns) { OrthonormalBasis<L>(ns, &s, &t); }
    V3<typename L::F> ToLocal(V3<typename L::F> w) const {
        return {Dot(w, s), Dot(w, t), Dot(w, n)};
    }
    V3<typename L::F> ToWorld(V3<typename L::F> w) const { return s * w.x + t * w.y + n * w.z; }
};

// f |cos theta_i| and the density of sampling wi, for world directions about ns, in the lanes of
// a glossy lobe (some lane has one). Where a vector mixes lobes, the first present gives the
// result and the others' lanes are selected in.
template <class L>
HWY_INLINE V3<typename L::F> GlossyEval(const LaneBsdf<L>& b,
                                        V3<typename L::F> ns,
                                        V3<typename L::F> wo,
                                        V3<typename L::F> wi,
                                        typename L::F* pdf) {
    using F = typename L::F;
    const GlossyFrame<L> frame(ns);
    const V3<F> lo = frame.ToLocal(wo), li = frame.ToLocal(wi);
    const F zero = L::Set(0.0f);
    bool first = true;
    V3<F> f{zero, zero, zero};
    *pdf = zero;
    auto take = [&](typename L::M m, V3<F> f_lobe, F pdf_lobe) {
        f = first ? f_lobe : Select3<L>(m, f_lobe, f);
        *pdf = first ? pdf_lobe : L::Select(m, pdf_lobe, *pdf);
        first = false;
    };
    F p;
    if (L::Any(b.metal)) {
        const V3<F> f_metal = MetalEval<L>(b.albedo, b.alpha, lo, li, &p);
        take(b.metal, f_metal, p);
    }
    if (L::Any(b.conductor)) {
        const V3<F> f_conductor = RoughConductorEval<L>(b.as_conductor(), lo, li, &p);
        take(b.conductor, f_conductor, p);
    }
    if (L::Any(b.dielectric)) {
        const F f_dielectric = RoughDielectricEval<L>(b.as_dielectric(), b.eta.x, lo, li, &p);
        take(b.dielectric, V3<F>{f_dielectric, f_dielectric, f_dielectric}, p);
    }
    if (L::Any(b.metallic_roughness)) {
        const V3<F> f_mr = MetallicRoughnessEval<L>(b.as_metallic_roughness(), lo, li, &p);
        take(b.metallic_roughness, f_mr, p);
    }
    return f;
}

// A sample of a glossy lobe: a reflection, or a transmission (a dielectric's refraction, a
// metallic-roughness surface's thin-walled transmission).
template <class L>
struct GlossyLobeSample {
    typename L::M valid;
    V3<typename L::F> wi;      // a world direction
    V3<typename L::F> weight;  // f |cos| / pdf
    typename L::F pdf;
    typename L::M transmitted;  // wi leaves through the shading surface (a dielectric's)
};

// A direction by the visible normals of each lane's glossy lobe (a metallic-roughness one picks
// its lobe by u_lobe, the cosine or the visible normals; a dielectric reflects with Fresnel's
// probability u_lobe < F), as a world direction; some lane has a glossy lobe.
template <class L>
HWY_INLINE GlossyLobeSample<L> GlossySample(const LaneBsdf<L>& b,
                                            V3<typename L::F> ns,
                                            V3<typename L::F> wo,
                                            typename L::F u_lobe,
                                            typename L::F u1,
                                            typename L::F u2) {
    const GlossyFrame<L> frame(ns);
    const V3<typename L::F> lo = frame.ToLocal(wo);
    const typename L::M none = L::Not(L::All());
    bool first = true;
    GlossyLobeSample<L> s;
    auto take = [&](typename L::M m, const ReflectionSample<L>& r, typename L::M transmitted) {
        if (first) {
            s = {r.valid, r.wi, r.weight, r.pdf, transmitted};
        } else {
            s.valid = L::Or(L::And(m, r.valid), L::AndNot(m, s.valid));
            s.wi = Select3<L>(m, r.wi, s.wi);
            s.weight = Select3<L>(m, r.weight, s.weight);
            s.pdf = L::Select(m, r.pdf, s.pdf);
            s.transmitted = L::Or(L::And(m, transmitted), L::AndNot(m, s.transmitted));
        }
        first = false;
    };
    if (L::Any(b.metal)) take(b.metal, MetalSample<L>(b.albedo, b.alpha, lo, u1, u2), none);
    if (L::Any(b.conductor))
        take(b.conductor, RoughConductorSample<L>(b.as_conductor(), lo, u1, u2), none);
    if (L::Any(b.dielectric)) {
        const DielectricSample<L> r =
            RoughDielectricSample<L>(b.as_dielectric(), b.eta.x, lo, u_lobe, u1, u2);
        take(b.dielectric, {r.valid, r.wi, V3<typename L::F>{r.weight, r.weight, r.weight}, r.pdf},
             r.transmitted);
    }
    if (L::Any(b.metallic_roughness)) {
        const MetallicRoughnessSampleResult<L> r =
            MetallicRoughnessSample<L>(b.as_metallic_roughness(), lo, u_lobe, u1, u2);
        take(b.metallic_roughness, {r.valid, r.wi, r.weight, r.pdf}, r.transmitted);
    }
    s.wi = frame.ToWorld(s.wi);
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_GLOSSY_INL_H_
