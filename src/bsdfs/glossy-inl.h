// The glossy lobes of the lane vertices over lanes: a rough metal (ggx-inl.h) or a rough
// conductor (conductor-inl.h), isotropic, each lane of its own, in world directions about the
// shading normal. An isotropic lobe needs no tangent, so the frame is OrthonormalBasis(ns) and
// nothing of the hit's dp/du. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_GLOSSY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_GLOSSY_INL_H_
#undef WAVETRACE_BSDFS_GLOSSY_INL_H_
#else
#define WAVETRACE_BSDFS_GLOSSY_INL_H_
#endif

#include "bsdfs/conductor-inl.h"
#include "bsdfs/ggx-inl.h"
#include "math/lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

template <class L>
struct GlossyLanes {
    V3<typename L::F> albedo;  // a metal's F0; a conductor's reflectance factor
    typename L::F alpha;       // roughness (> 0)
    V3<typename L::F> eta, k;  // conductor: the complex index of refraction
    typename L::M beckmann;    // conductor: a Beckmann distribution, else GGX
    typename L::M conductor;   // the lanes of a conductor; the others are metals

    RoughConductor<L> as_conductor() const { return {albedo, eta, k, {beckmann, alpha, alpha}}; }
};

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

// f |cos theta_i| and the density of sampling wi, for world directions about ns.
template <class L>
HWY_INLINE V3<typename L::F> GlossyEval(const GlossyLanes<L>& g,
                                        V3<typename L::F> ns,
                                        V3<typename L::F> wo,
                                        V3<typename L::F> wi,
                                        typename L::F* pdf) {
    using F = typename L::F;
    const GlossyFrame<L> frame(ns);
    const V3<F> lo = frame.ToLocal(wo), li = frame.ToLocal(wi);
    const bool any_metal = L::Any(L::Not(g.conductor));
    V3<F> f = any_metal ? MetalEval<L>(g.albedo, g.alpha, lo, li, pdf)
                        : RoughConductorEval<L>(g.as_conductor(), lo, li, pdf);
    if (any_metal && L::Any(g.conductor)) {
        F pdf_conductor;
        const V3<F> f_conductor = RoughConductorEval<L>(g.as_conductor(), lo, li, &pdf_conductor);
        f = Select3<L>(g.conductor, f_conductor, f);
        *pdf = L::Select(g.conductor, pdf_conductor, *pdf);
    }
    return f;
}

// A direction by the visible normals of each lane's lobe, as a world direction.
template <class L>
HWY_INLINE ReflectionSample<L> GlossySample(const GlossyLanes<L>& g,
                                            V3<typename L::F> ns,
                                            V3<typename L::F> wo,
                                            typename L::F u1,
                                            typename L::F u2) {
    const GlossyFrame<L> frame(ns);
    const V3<typename L::F> lo = frame.ToLocal(wo);
    // The first lobe present gives the vector's result, the other's lanes are selected in.
    const bool any_metal = L::Any(L::Not(g.conductor));
    ReflectionSample<L> s = any_metal ? MetalSample<L>(g.albedo, g.alpha, lo, u1, u2)
                                      : RoughConductorSample<L>(g.as_conductor(), lo, u1, u2);
    if (any_metal && L::Any(g.conductor)) {
        const ReflectionSample<L> c = RoughConductorSample<L>(g.as_conductor(), lo, u1, u2);
        s.valid = L::Or(L::And(g.conductor, c.valid), L::AndNot(g.conductor, s.valid));
        s.wi = Select3<L>(g.conductor, c.wi, s.wi);
        s.weight = Select3<L>(g.conductor, c.weight, s.weight);
        s.pdf = L::Select(g.conductor, c.pdf, s.pdf);
    }
    s.wi = frame.ToWorld(s.wi);
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_GLOSSY_INL_H_
