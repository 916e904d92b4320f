// glTF's metallic-roughness material over lanes: the lobe choice, the value and density of its
// glossy and diffuse lobes (the specular, diffuse, clearcoat and thin-walled transmission lobes
// of metallic_roughness.h, which states the model), and a direction sampled from them.
// metallic_roughness.cpp runs the one-lane instances; the smooth (Dirac delta) lobes stay there.
// Directions are in the shading frame. Per-target header, see math/lanes-inl.h.
#if defined(WAVETRACE_BSDFS_METALLIC_ROUGHNESS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef WAVETRACE_BSDFS_METALLIC_ROUGHNESS_INL_H_
#undef WAVETRACE_BSDFS_METALLIC_ROUGHNESS_INL_H_
#else
#define WAVETRACE_BSDFS_METALLIC_ROUGHNESS_INL_H_
#endif

#include "bsdfs/metal-inl.h"
#include "math/lanes-inl.h"
#include "sampling/warp-inl.h"
#include "wavetrace/math/constants.h"

HWY_BEFORE_NAMESPACE();
namespace wavetrace {
namespace HWY_NAMESPACE {

template <class L>
struct MetallicRoughnessLanes {
    V3<typename L::F> albedo;  // the base colour c
    typename L::F alpha;       // the specular lobes' GGX alpha (0: smooth)
    typename L::F f0;          // the dielectric's Schlick F0, from its IOR (schlick_f0)
    typename L::F metallic, transmission, clearcoat;
    typename L::F coat_alpha;  // the clearcoat's GGX alpha (0: smooth)
    V3<typename L::F> coat_n;  // the clearcoat's normal (unit; (0, 0, 1): the shading normal)
    typename L::M one_sided;   // black from behind
};

// The material as o's side sees it (side -1: from behind, where both directions are mirrored
// through the surface, Upper): the coat's normal seen from behind is -coat_n, and mirrored
// that is coat_n with its tangential part negated.
template <class L>
HWY_INLINE MetallicRoughnessLanes<L> SeenFrom(const MetallicRoughnessLanes<L>& b,
                                              typename L::F side) {
    MetallicRoughnessLanes<L> s = b;
    s.coat_n = {b.coat_n.x * side, b.coat_n.y * side, b.coat_n.z};
    return s;
}

// The probabilities of the lobes for o (o.z > 0), in proportion to their shares of the light
// at V.h = N.V; they sum to 1, or are all 0 where nothing is reflected.
template <class L>
struct MetallicRoughnessLobes {
    typename L::F coat, specular, diffuse, transmission;
};

template <class L>
HWY_INLINE typename L::F Mean3(V3<typename L::F> a) {
    return (a.x + a.y + a.z) / L::Set(3.0f);
}

// The clearcoat's Fresnel at the view direction, 0.04 + 0.96 s(N_c.V) of its normal N_c, for
// oc = N_c.V (0 without a clearcoat, and where V lies behind N_c: the coat reflects nothing
// there).
template <class L>
HWY_INLINE typename L::F CoatFresnel(const MetallicRoughnessLanes<L>& b, typename L::F oc) {
    const typename L::F zero = L::Set(0.0f);
    return L::Select(L::And(b.clearcoat > zero, oc > zero),
                     L::Set(0.04f) + L::Set(0.96f) * SchlickWeight<L>(oc), zero);
}

template <class L>
HWY_INLINE MetallicRoughnessLobes<L> ChooseMetallicRoughnessLobes(
    const MetallicRoughnessLanes<L>& b, V3<typename L::F> o) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f);
    const F s = SchlickWeight<L>(o.z);
    const F fd = b.f0 + (one - b.f0) * s;
    const F fm =
        Mean3<L>(b.albedo + V3<F>{one - b.albedo.x, one - b.albedo.y, one - b.albedo.z} * s);
    const F fc = CoatFresnel<L>(b, Dot(o, b.coat_n)), base = one - b.clearcoat * fc;
    const F m = b.metallic, c = Mean3<L>(b.albedo);
    MetallicRoughnessLobes<L> p;
    p.coat = b.clearcoat * fc;
    // At least 2% of the base for the specular lobe: a black metal still reflects at grazing
    // half vectors, and a lobe with f > 0 must have a density there.
    p.specular = base * L::Max((one - m) * fd + m * fm, L::Set(0.02f));
    p.diffuse = base * (one - m) * (one - b.transmission) * (one - fd) * c;
    p.transmission = base * (one - m) * b.transmission * (one - fd) * c;
    const F sum = p.coat + p.specular + p.diffuse + p.transmission;
    const auto positive = sum > zero;
    const F inv = one / L::Select(positive, sum, one);
    p.coat = L::Select(positive, p.coat * inv, zero);
    p.specular = L::Select(positive, p.specular * inv, zero);
    p.diffuse = L::Select(positive, p.diffuse * inv, zero);
    p.transmission = L::Select(positive, p.transmission * inv, zero);
    return p;
}

// f cos_i of the lobes that are not deltas, and their density weighted by the lobe
// probabilities p, for o above the surface (o.z > 0) and i on either side: above, the diffuse,
// specular and clearcoat lobes; below, the thin-walled transmission, whose half vector is that
// of i mirrored through the surface. 0 and density 0 where no lobe has a density. The coat's
// lobe lies about its own normal N_c: D(h.N_c) G1(o.N_c) G1(i.N_c) / (4 (o.N_c) (i.N_c)) times
// cos_i = i.z; its density, that of the visible normals about N_c, counts every i above the
// surface that they reach, also where i.N_c <= 0 and the lobe's value is 0.
template <class L>
HWY_INLINE V3<typename L::F> MetallicRoughnessUpper(const MetallicRoughnessLanes<L>& b,
                                                    const MetallicRoughnessLobes<L>& p,
                                                    V3<typename L::F> o,
                                                    V3<typename L::F> i,
                                                    typename L::F* pdf) {
    using F = typename L::F;
    const F zero = L::Set(0.0f), one = L::Set(1.0f), four_cos = L::Set(4.0f) * o.z;
    const F m = b.metallic;
    const F oc = Dot(o, b.coat_n);
    const F fc = CoatFresnel<L>(b, oc), base = one - b.clearcoat * fc;
    const auto above = i.z > zero;
    const auto rough = b.alpha > zero;
    const auto below = L::And(L::And(i.z < zero, rough), b.transmission > zero);
    // The half vector of i, or of i mirrored through the surface.
    const V3<F> im{i.x, i.y, L::Abs(i.z)};
    const V3<F> h = Normalize<L>(o + im);
    const F fd = b.f0 + (one - b.f0) * SchlickWeight<L>(Dot(o, h));
    const F alpha = L::Select(rough, b.alpha, one);  // the lobe is 0 where smooth
    const F d = L::Select(rough, GgxD<L>(h.z, alpha), zero), g1_o = GgxG1<L>(o.z, alpha);
    const F spec = d * g1_o * GgxG1<L>(im.z, alpha) / four_cos;
    const F spec_pdf = g1_o * d / four_cos;
    // Below: the transmission lobe.
    V3<F> f = b.albedo * (base * (one - m) * b.transmission * (one - fd) * spec);
    F density = p.transmission * spec_pdf;
    if (L::Any(above)) {
        const F s = SchlickWeight<L>(Dot(o, h));
        const V3<F> fm = b.albedo + V3<F>{one - b.albedo.x, one - b.albedo.y, one - b.albedo.z} * s;
        const F cos_pi = i.z * L::Set(kInvPi);
        V3<F> up = b.albedo * (base * (one - m) * (one - b.transmission) * (one - fd) * cos_pi);
        F up_pdf = p.diffuse * cos_pi;
        const F dielectric = (one - m) * fd;
        up = up + (V3<F>{dielectric, dielectric, dielectric} + fm * m) * (base * spec);
        up_pdf = up_pdf + p.specular * spec_pdf;
        // fc > 0: a coat that o sees (oc > 0).
        const auto coated = L::And(fc > zero, b.coat_alpha > zero);
        if (L::Any(coated)) {
            const F a = L::Select(coated, b.coat_alpha, one);
            const F ic = Dot(i, b.coat_n), hc = Dot(h, b.coat_n);
            const auto lit = L::And(coated, ic > zero);
            // Where N_c is the shading normal, i.z / ic = 1 and this is D G1 G1 / (4 o.z).
            const F ic_lit = L::Select(lit, ic, one),
                    four_oc = L::Set(4.0f) * L::Select(coated, oc, one);
            const F dc = L::Select(coated, GgxD<L>(hc, a), zero), gc_o = GgxG1<L>(oc, a);
            const F coat = L::Select(
                lit, b.clearcoat * fc * dc * gc_o * GgxG1<L>(ic_lit, a) * (i.z / ic_lit) / four_oc,
                zero);
            up = up + V3<F>{coat, coat, coat};
            up_pdf = up_pdf + p.coat * gc_o * dc / four_oc;
        }
        f = Select3<L>(above, up, f);
        density = L::Select(above, up_pdf, density);
    }
    return ValueWhere<L>(L::And(L::Or(above, below), density > zero), f, density, pdf);
}

// Whether wo sees the surface: not at grazing, and not from behind a one-sided one.
template <class L>
HWY_INLINE typename L::M SeesSurface(const MetallicRoughnessLanes<L>& b, typename L::F wo_z) {
    const typename L::F zero = L::Set(0.0f);
    return L::Not(L::Or(wo_z == zero, L::And(b.one_sided, wo_z < zero)));
}

// The same for any wo, wi: from behind (wo.z < 0) both are mirrored, or, one-sided, nothing.
template <class L>
HWY_INLINE V3<typename L::F> MetallicRoughnessEval(const MetallicRoughnessLanes<L>& b,
                                                   V3<typename L::F> wo,
                                                   V3<typename L::F> wi,
                                                   typename L::F* pdf) {
    using F = typename L::F;
    const F side = SideOf<L>(wo);
    const V3<F> o = Upper<L>(wo, side);
    const MetallicRoughnessLanes<L> seen = SeenFrom<L>(b, side);
    F p;
    const V3<F> f = MetallicRoughnessUpper<L>(seen, ChooseMetallicRoughnessLobes<L>(seen, o), o,
                                              Upper<L>(wi, side), &p);
    return ValueWhere<L>(L::And(SeesSurface<L>(b, wo.z), p > L::Set(0.0f)), f, p, pdf);
}

template <class L>
struct MetallicRoughnessSampleResult {
    typename L::M valid;  // false: no lobe, a smooth one (metallic_roughness.cpp's), or lost
    V3<typename L::F> wi;
    V3<typename L::F> weight;  // f |cos| / pdf
    typename L::F pdf;
    typename L::M transmitted;  // wi crossed the surface
};

// A direction from the rough lobes for o above the surface (o.z > 0), of lobe probabilities p:
// u_lobe picks the lobe, (u1, u2) the direction, by the cosine or the visible normals of GGX (the
// transmission lobe's reflection mirrored through the surface); its value and density from
// (o, i) as MetallicRoughnessUpper computes them, so that weight = eval / pdf. Lanes whose
// choice is a smooth lobe are not valid.
template <class L>
HWY_INLINE MetallicRoughnessSampleResult<L> MetallicRoughnessSampleUpper(
    const MetallicRoughnessLanes<L>& b,
    const MetallicRoughnessLobes<L>& p,
    V3<typename L::F> o,
    typename L::F u_lobe,
    typename L::F u1,
    typename L::F u2) {
    using F = typename L::F;
    const F zero = L::Set(0.0f);
    MetallicRoughnessSampleResult<L> s;
    const auto coat = u_lobe < p.coat;
    const auto specular = L::AndNot(coat, u_lobe < p.coat + p.specular);
    const auto diffuse = L::AndNot(L::Or(coat, specular), u_lobe < p.coat + p.specular + p.diffuse);
    const auto transmission =
        L::AndNot(L::Or(L::Or(coat, specular), diffuse), p.transmission > zero);
    const F alpha = L::Select(coat, b.coat_alpha, b.alpha);
    const auto smooth = L::AndNot(diffuse, L::Not(alpha > zero));
    auto ok = L::AndNot(smooth, L::Or(L::Or(coat, specular), L::Or(diffuse, transmission)));
    s.wi = CosineHemisphere<L>(u1, u2);
    if (L::Any(L::AndNot(diffuse, ok))) {
        const F a = L::Select(alpha > zero, alpha, L::Set(1.0f));
        // The coat's visible normals about its own normal (o.N_c > 0 where it is chosen), in a
        // frame of which N_c is z.
        const auto tilted = L::And(coat, L::Not(L::And(b.coat_n.x == zero, b.coat_n.y == zero)));
        V3<F> cs, ct, ol = o;
        if (L::Any(tilted)) {
            OrthonormalBasis<L>(b.coat_n, &cs, &ct);
            ol = Select3<L>(tilted, V3<F>{Dot(o, cs), Dot(o, ct), Dot(o, b.coat_n)}, o);
        }
        V3<F> n = GgxVisibleNormal<L>(ol, a, a, u1, u2);
        if (L::Any(tilted)) n = Select3<L>(tilted, cs * n.x + ct * n.y + b.coat_n * n.z, n);
        V3<F> r = Reflect<L>(o, n);
        ok = L::AndNot(L::AndNot(diffuse, L::Not(r.z > zero)), ok);  // below the surface: lost
        r.z = L::Select(transmission, L::Neg(r.z), r.z);
        s.wi = Select3<L>(diffuse, s.wi, r);
    }
    const V3<F> f = MetallicRoughnessUpper<L>(b, p, o, s.wi, &s.pdf);
    s.valid = L::And(ok, s.pdf > zero);
    s.weight = f * (L::Set(1.0f) / L::Select(s.valid, s.pdf, L::Set(1.0f)));
    s.transmitted = transmission;
    return s;
}

// The same for any wo: from behind (wo.z < 0) both directions are mirrored, or, one-sided,
// nothing is valid.
template <class L>
HWY_INLINE MetallicRoughnessSampleResult<L> MetallicRoughnessSample(
    const MetallicRoughnessLanes<L>& b,
    V3<typename L::F> wo,
    typename L::F u_lobe,
    typename L::F u1,
    typename L::F u2) {
    using F = typename L::F;
    const F side = SideOf<L>(wo);
    const V3<F> o = Upper<L>(wo, side);
    const MetallicRoughnessLanes<L> seen = SeenFrom<L>(b, side);
    MetallicRoughnessSampleResult<L> s = MetallicRoughnessSampleUpper<L>(
        seen, ChooseMetallicRoughnessLobes<L>(seen, o), o, u_lobe, u1, u2);
    s.valid = L::And(SeesSurface<L>(b, wo.z), s.valid);
    s.wi = Upper<L>(s.wi, side);
    return s;
}

}  // namespace HWY_NAMESPACE
}  // namespace wavetrace
HWY_AFTER_NAMESPACE();

#endif  // WAVETRACE_BSDFS_METALLIC_ROUGHNESS_INL_H_
