// The GGX (Trowbridge-Reitz) distribution of microfacet normals over lanes: its density and
// Smith's Lambda, isotropic and anisotropic (Walter et al. 2007; Heitz 2014), and the sampling
// of its visible normals (Heitz 2018). MicrofacetDistribution (microfacet.h) runs the one-lane
// instances; the lane lobes of bsdfs/ run them over vectors. Directions are in the shading
// frame, z along the normal. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_MICROFACETS_GGX_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_MICROFACETS_GGX_INL_H_
#undef WAVETRACE_MICROFACETS_GGX_INL_H_
#else
#define WAVETRACE_MICROFACETS_GGX_INL_H_
#endif

#include "math/lanes-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// Smith's Lambda for GGX of a direction with cosine z: (-1 + sqrt(1 + alpha^2 tan^2)) / 2
// (Heitz 2014, eq. 72); infinite at grazing.
template <class L>
HWY_INLINE typename L::F GgxLambda(typename L::F z, typename L::F alpha) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F cos2 = z * z;
    const F tan2 = L::Max(zero, one - cos2) / cos2;
    const F lambda = L::Set(0.5f) * (L::Set(-1.0f) + L::Sqrt(one + alpha * alpha * tan2));
    return L::Select(cos2 <= zero, L::Set(kInfinity), lambda);
}

template <class L>
HWY_INLINE typename L::F GgxG1(typename L::F z, typename L::F alpha) {
    return L::Set(1.0f) / (L::Set(1.0f) + GgxLambda<L>(z, alpha));
}

// The GGX distribution of microfacet normals with cosine hz: alpha^2 / (pi t^2),
// t = hz^2 (alpha^2 - 1) + 1; zero below the surface.
template <class L>
HWY_INLINE typename L::F GgxD(typename L::F hz, typename L::F alpha) {
    using F = typename L::F;
    const F a2 = alpha * alpha;
    const F t = hz * hz * (a2 - L::Set(1.0f)) + L::Set(1.0f);
    return L::Select(hz <= L::Set(0.0f), L::Set(0.0f), a2 / (L::Set(kPi) * t * t));
}

// The anisotropic GGX distribution (the rough conductor's, dielectric's and plastic's, through
// microfacet-inl.h): D(m) = 1 / (pi au av (mx^2/au^2 + my^2/av^2 + mz^2)^2) (Walter et al.
// 2007); 0 for mz <= 0.
template <class L>
HWY_INLINE typename L::F GgxAnisotropicD(V3<typename L::F> m, typename L::F au, typename L::F av) {
    using F = typename L::F;
    const F xu = m.x / au, yv = m.y / av;
    const F t = xu * xu + yv * yv + m.z * m.z;
    return L::Select(m.z <= L::Set(0.0f), L::Set(0.0f),
                     L::Set(1.0f) / (L::Set(kPi) * au * av * t * t));
}

// Its Smith Lambda(w) = (-1 + sqrt(1 + q)) / 2 with q = (au^2 wx^2 + av^2 wy^2) / wz^2 = alpha^2
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

// A visible normal of the GGX distribution of roughness alpha_x, alpha_y along the frame's x
// and y seen from o (upper hemisphere): stretch to the hemisphere configuration, sample the
// projected half-disk, unstretch (Heitz 2018, "Sampling the GGX Distribution of Visible
// Normals", JCGT 7(4)).
template <class L>
HWY_INLINE V3<typename L::F> GgxVisibleNormal(V3<typename L::F> o,
                                              typename L::F alpha_x,
                                              typename L::F alpha_y,
                                              typename L::F u1,
                                              typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const V3<F> vh = Normalize<L>(V3<F>{alpha_x * o.x, alpha_y * o.y, o.z});
    const F lensq = vh.x * vh.x + vh.y * vh.y;
    const F inv = one / L::Sqrt(lensq);
    const auto tilted = lensq > zero;
    const V3<F> t1{L::Select(tilted, L::Neg(vh.y) * inv, one), L::Select(tilted, vh.x * inv, zero),
                   L::Select(tilted, zero * inv, zero)};
    const V3<F> t2 = Cross(vh, t1);
    const F r = L::Sqrt(u1);
    F sin_phi, cos_phi;
    SinCos2Pi<L>(u2, &sin_phi, &cos_phi);
    const F p1 = r * cos_phi;
    const F s = L::Set(0.5f) * (one + vh.z);
    const F p2 = (one - s) * L::Sqrt(L::Max(zero, one - p1 * p1)) + s * (r * sin_phi);
    const V3<F> nh = t1 * p1 + t2 * p2 + vh * L::Sqrt(L::Max(zero, one - p1 * p1 - p2 * p2));
    return Normalize<L>(V3<F>{alpha_x * nh.x, alpha_y * nh.y, L::Max(L::Set(1e-7f), nh.z)});
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_MICROFACETS_GGX_INL_H_
