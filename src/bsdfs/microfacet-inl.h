// Microfacet normal distributions over lanes, GGX (Trowbridge-Reitz) or Beckmann per lane,
// anisotropic with roughness alpha_u along the shading frame's x axis and alpha_v along its y,
// with Smith's masking and sampling of the visible normals: the formulas of microfacet.h, which
// runs their one-lane instances. Directions are unit vectors in the shading frame (z along the
// normal), m a microfacet normal. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_MICROFACET_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_MICROFACET_INL_H_
#undef WAVETRACE_BSDFS_MICROFACET_INL_H_
#else
#define WAVETRACE_BSDFS_MICROFACET_INL_H_
#endif

#include "bsdfs/beckmann-inl.h"
#include "bsdfs/ggx-inl.h"
#include "math/lanes-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

template <class L>
struct MicrofacetLanes {
    typename L::M beckmann;          // else GGX
    typename L::F alpha_u, alpha_v;  // > 0
};

// GGX: D(m) = 1 / (pi au av (mx^2/au^2 + my^2/av^2 + mz^2)^2) (Walter et al. 2007); 0 for
// mz <= 0.
template <class L>
HWY_INLINE typename L::F GgxAnisotropicD(V3<typename L::F> m, typename L::F au, typename L::F av) {
    using F = typename L::F;
    const F xu = m.x / au, yv = m.y / av;
    const F t = xu * xu + yv * yv + m.z * m.z;
    return L::Select(m.z <= L::Set(0.0f), L::Set(0.0f),
                     L::Set(1.0f) / (L::Set(kPi) * au * av * t * t));
}

// GGX: Lambda(w) = (-1 + sqrt(1 + q)) / 2 with q = (au^2 wx^2 + av^2 wy^2) / wz^2 = alpha^2
// tan^2 theta along w's azimuth (Heitz 2014, eq. 72), as q / (2 (1 + sqrt(1 + q))), which
// does not cancel for small q; 0 along the normal, infinite at grazing.
template <class L>
HWY_INLINE typename L::F GgxAnisotropicLambda(V3<typename L::F> w,
                                              typename L::F au,
                                              typename L::F av) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F x = au * w.x, y = av * w.y;
    const F r2 = x * x + y * y, z2 = w.z * w.z;
    const auto grazing = z2 <= zero;
    const F q = r2 / L::Select(grazing, one, z2);
    const F lambda = L::Set(0.5f) * q / (one + L::Sqrt(one + q));
    return L::Select(r2 <= zero, zero, L::Select(grazing, L::Set(kInfinity), lambda));
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

#endif  // WAVETRACE_BSDFS_MICROFACET_INL_H_
