// Microfacet normal distributions over lanes, GGX (Trowbridge-Reitz, ggx-inl.h) or Beckmann
// (beckmann-inl.h) per lane, anisotropic with roughness alpha_u along the shading frame's x axis
// and alpha_v along its y, with Smith's masking and sampling of the visible normals: the
// formulas of microfacet.h, which runs their one-lane instances. Directions are unit vectors in the
// shading frame (z along the normal), m a microfacet normal. Per-target header, see
// math/lanes-inl.h.
#if defined(WAVETRACE_MICROFACETS_MICROFACET_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_MICROFACETS_MICROFACET_INL_H_
#undef WAVETRACE_MICROFACETS_MICROFACET_INL_H_
#else
#define WAVETRACE_MICROFACETS_MICROFACET_INL_H_
#endif

#include "math/lanes-inl.h"
#include "microfacets/beckmann-inl.h"
#include "microfacets/ggx-inl.h"
#include "microfacets/microfacet.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

template <class L>
struct MicrofacetLanes {
    typename L::M beckmann;          // else GGX
    typename L::F alpha_u, alpha_v;  // > 0
};

// The one-lane view of the distribution d.
inline MicrofacetLanes<OneLane> to_lanes(const MicrofacetDistribution& d) {
    return {d.kind == Microfacet::Beckmann, d.alpha_u, d.alpha_v};
}

// D(m): the density of microfacet normals per unit projected area (the integral of D(m) m.z
// over the hemisphere is 1); 0 for m.z <= 0.
template <class L>
HWY_INLINE typename L::F MicrofacetD(const MicrofacetLanes<L>& md, V3<typename L::F> m) {
    typename L::F d = L::Set(0.0f);
    if (L::Any(L::Not(md.beckmann))) d = GgxAnisotropicD<L>(m, md.alpha_u, md.alpha_v);
    if (L::Any(md.beckmann)) d = L::Select(md.beckmann, BeckmannD<L>(m, md.alpha_u, md.alpha_v), d);
    return d;
}

// Smith's Lambda(w) (Heitz 2014, §5.1-5.2).
template <class L>
HWY_INLINE typename L::F MicrofacetLambda(const MicrofacetLanes<L>& md, V3<typename L::F> w) {
    typename L::F lambda = L::Set(0.0f);
    if (L::Any(L::Not(md.beckmann))) lambda = GgxAnisotropicLambda<L>(w, md.alpha_u, md.alpha_v);
    if (L::Any(md.beckmann))
        lambda = L::Select(md.beckmann, BeckmannLambda<L>(w, md.alpha_u, md.alpha_v), lambda);
    return lambda;
}

// A normal drawn with the density of visible normals from wo (wo.z > 0): GGX by Heitz 2018,
// Beckmann by Heitz & d'Eon 2014 (ggx-inl.h, beckmann-inl.h).
template <class L>
HWY_INLINE V3<typename L::F> MicrofacetVisibleNormal(const MicrofacetLanes<L>& md,
                                                     V3<typename L::F> wo,
                                                     typename L::F u1,
                                                     typename L::F u2) {
    using F = typename L::F;
    V3<F> m{L::Set(0.0f), L::Set(0.0f), L::Set(1.0f)};
    if (L::Any(L::Not(md.beckmann))) m = GgxVisibleNormal<L>(wo, md.alpha_u, md.alpha_v, u1, u2);
    if (L::Any(md.beckmann))
        m = Select3<L>(md.beckmann, BeckmannVisibleNormal<L>(wo, md.alpha_u, md.alpha_v, u1, u2),
                       m);
    return m;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_MICROFACETS_MICROFACET_INL_H_
