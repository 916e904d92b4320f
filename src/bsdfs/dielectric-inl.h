// A dielectric interface over lanes: Fresnel's reflectance, Snell's refraction about a
// microfacet normal, and the rough dielectric (Walter et al. 2007, "Microfacet Models for
// Refraction through Rough Surfaces"), GGX or Beckmann, sampled by the visible normals of wo's
// side. fresnel_dielectric, refract and rough_dielectric_eval / _sample run the one-lane
// instances; the wavefront's lane vertices run them over vectors. Directions are in the
// shading frame, z along the normal; eta is the index of the side below over the side above.
// Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_DIELECTRIC_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_DIELECTRIC_INL_H_
#undef WAVETRACE_BSDFS_DIELECTRIC_INL_H_
#else
#define WAVETRACE_BSDFS_DIELECTRIC_INL_H_
#endif

#include "math/lanes-inl.h"
#include "microfacets/microfacet-inl.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

// The relative index a direction of cosine cos_o to the normal meets at a dielectric of index
// eta (the side below over the side above): eta from above, where it enters the material,
// 1 / eta from below.
template <class L>
HWY_INLINE typename L::F SeenEta(typename L::F eta, typename L::F cos_o) {
    return L::Select(cos_o > L::Set(0.0f), eta, L::Set(1.0f) / eta);
}

// Unpolarized Fresnel reflectance for light arriving at cos_i > 0 on a dielectric of relative
// index eta (the mean of the s and p polarizations); 1 under total internal reflection.
template <class L>
HWY_INLINE typename L::F FresnelDielectric(typename L::F cos_i, typename L::F eta) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F sin2_t = L::Max(zero, one - cos_i * cos_i) / (eta * eta);
    const auto total = sin2_t >= one;
    const F cos_t = L::Sqrt(L::Select(total, zero, one - sin2_t));
    const F r_par = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    const F r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    return L::Select(total, one, L::Set(0.5f) * (r_par * r_par + r_perp * r_perp));
}

// Snell's law about a microfacet normal m on o's side (o.m > 0), eta the index of the side i
// enters over o's: i = -o / eta + ((o.m) / eta - cos_t) m, normalized; false (and i
// meaningless) under total internal reflection.
template <class L>
HWY_INLINE typename L::M Refract(V3<typename L::F> o,
                                 V3<typename L::F> m,
                                 typename L::F eta,
                                 V3<typename L::F>* i) {
    using F = typename L::F;
    const F one = L::Set(1.0f);
    const F cos_om = Dot(o, m);
    const F sin2_t = (one - cos_om * cos_om) / (eta * eta);
    const auto refracts = sin2_t < one;
    const F cos_t = L::Sqrt(L::Select(refracts, one - sin2_t, L::Set(0.0f)));
    *i = Normalize<L>(Neg3<L>(o) * (one / eta) + m * (cos_om / eta - cos_t));
    return refracts;
}

// f |cos theta_i| and the density of sampling i, for o above the surface (o.z > 0) and i on
// either side, eta the index below over above: reflection about the half vector o + i,
// refraction about -(eta i + o), each weighted by Fresnel at the microfacet; valid where the
// microfacet faces o and i leaves on the side the event requires.
template <class L>
HWY_INLINE typename L::F RoughDielectricUpper(const MicrofacetLanes<L>& md,
                                              typename L::F eta,
                                              V3<typename L::F> o,
                                              V3<typename L::F> i,
                                              typename L::F* pdf) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f), four = L::Set(4.0f);
    const auto reflect = i.z > zero;
    V3<F> h = Select3<L>(reflect, o + i, Neg3<L>(i * eta + o));
    const F h2 = Dot(h, h);
    auto ok = h2 > zero;
    h = h * (one / L::Sqrt(L::Select(ok, h2, one)));
    h = Select3<L>(h.z < zero, Neg3<L>(h), h);
    const F cos_oh = Dot(o, h), cos_ih = Dot(i, h);
    ok = L::And(ok, L::And(cos_oh > zero, L::Select(reflect, cos_ih, L::Neg(cos_ih)) > zero));
    const F f = FresnelDielectric<L>(cos_oh, eta);
    const F d = MicrofacetD<L>(md, h);
    const F lambda_o = MicrofacetLambda<L>(md, o);
    const F g2 = one / (one + lambda_o + MicrofacetLambda<L>(md, i));
    const F visible = one / (one + lambda_o) * cos_oh * d / o.z;  // D_o(h)
    const F denom = eta * cos_ih + cos_oh;
    const F abs_ih = L::Abs(cos_ih);
    const F jacobian = eta * eta * abs_ih / (denom * denom);
    const F p = L::Select(reflect, f * visible / (four * cos_oh), (one - f) * visible * jacobian);
    const F value = L::Select(reflect, f * d * g2 / (four * o.z),
                              abs_ih * cos_oh * (one - f) * d * g2 / (o.z * denom * denom));
    *pdf = L::Select(ok, p, zero);
    return L::Select(ok, value, zero);
}

// The rough dielectric of relative index eta (inside over outside; the shading normal points
// out): f |cos theta_i| (grey) and its density, wo and wi on either side, both mirrored above
// when wo is below (then the index seen is 1 / eta); 0 where either is grazing.
template <class L>
HWY_INLINE typename L::F RoughDielectricEval(const MicrofacetLanes<L>& md,
                                             typename L::F eta,
                                             V3<typename L::F> wo,
                                             V3<typename L::F> wi,
                                             typename L::F* pdf) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const auto below = wo.z < zero;
    const F side = L::Select(below, L::Neg(one), one);
    const F eta_seen = SeenEta<L>(eta, wo.z);
    F p;
    const F f = RoughDielectricUpper<L>(md, eta_seen, {wo.x, wo.y, wo.z * side},
                                        {wi.x, wi.y, wi.z * side}, &p);
    const auto valid = L::And(L::And(wo.z != zero, wi.z != zero), p > zero);
    *pdf = L::Select(valid, p, zero);
    return L::Select(valid, f, zero);
}

template <class L>
struct DielectricSample {
    typename L::M valid;  // false: wo grazing, or the sample leaves on the wrong side
    typename L::M transmitted;
    V3<typename L::F> wi;  // in the shading frame
    typename L::F weight;  // f |cos| / pdf, grey
    typename L::F pdf;
};

// A direction for wo: a visible normal m of wo's side, then reflection about it with Fresnel's
// probability F(o.m) (u_lobe < F) or refraction through it; the value and density recomputed
// from (o, i) as RoughDielectricUpper evaluates them, so that weight = eval / pdf to the bit.
template <class L>
HWY_INLINE DielectricSample<L> RoughDielectricSample(const MicrofacetLanes<L>& md,
                                                     typename L::F eta,
                                                     V3<typename L::F> wo,
                                                     typename L::F u_lobe,
                                                     typename L::F u1,
                                                     typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F side = L::Select(wo.z < zero, L::Neg(one), one);
    const F eta_seen = SeenEta<L>(eta, wo.z);
    const V3<F> o{wo.x, wo.y, wo.z * side};
    const V3<F> m = MicrofacetVisibleNormal<L>(md, o, u1, u2);
    const F cos_om = Dot(o, m);
    const F f = FresnelDielectric<L>(cos_om, eta_seen);
    const auto reflect = u_lobe < f;
    const V3<F> reflected = m * (L::Set(2.0f) * cos_om) - o;
    V3<F> refracted;
    const auto refracts = Refract<L>(o, m, eta_seen, &refracted);
    const V3<F> i = Select3<L>(reflect, reflected, refracted);
    auto ok = L::And(wo.z != zero, cos_om > zero);
    ok = L::And(ok, L::Select(reflect, i.z, L::Select(refracts, L::Neg(i.z), zero)) > zero);
    DielectricSample<L> s;
    const F value = RoughDielectricUpper<L>(md, eta_seen, o, i, &s.pdf);
    s.valid = L::And(ok, s.pdf > zero);
    s.transmitted = L::Not(reflect);
    s.wi = {i.x, i.y, i.z * side};
    s.weight = value * (one / L::Select(s.valid, s.pdf, one));
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_DIELECTRIC_INL_H_
