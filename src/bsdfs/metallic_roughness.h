// glTF 2.0's metallic-roughness material (the specification's Appendix B, "BRDF
// Implementation"), with KHR_materials_ior, KHR_materials_transmission (thin-walled) and
// KHR_materials_clearcoat. Contract as bsdf.h states it: directions in the shading frame pointing
// away from the vertex; eval() includes |cos theta_i|; sample()'s weight is f |cos| / pdf. Both
// sides alike (o below the surface: both directions mirrored), unless one_sided: black from
// behind.
//
// With c the base colour, m metallic, alpha = roughness^2 (GGX), V = o, L = i, h their half
// vector, s(x) = (1 - |x|)^5, Schlick's Fresnel with F0 = ((ior - 1) / (ior + 1))^2:
//   Fd = F0 + (1 - F0) s(V.h),  Fm = c + (1 - c) s(V.h),
//   specular = D(h) G1(V) G1(L) / (4 |N.V| |N.L|)   (GGX; the spec's separable Smith form)
//   metal      = Fm specular
//   dielectric = Fd specular + (1 - Fd) [(1 - t) c / pi + t c specular_T]
//   material   = (1 - m) dielectric + m metal
// where t is the transmission and specular_T the thin-walled microfacet BTDF: the specular lobe
// with L mirrored through the surface, h_T = normalize(V + L - 2 (N.L) N), no refraction (a
// surface of two back-to-back interfaces; KHR_materials_transmission's implementation notes).
// The clearcoat of weight k and roughness alpha_c lies on top, about a normal N_c of its own
// (KHR_materials_clearcoat's clearcoatNormal; BsdfParams::coat_normal, by default N):
//   coated = (1 - k Fc) material + k Fc specular(alpha_c, N_c),  Fc = 0.04 + 0.96 s(N_c.V),
// its Fresnel taken at the view direction as KHR_materials_clearcoat's fresnel_coat does, so
// the coated material is not reciprocal (the rest is). specular(alpha_c, N_c) is the specular
// lobe with N_c for N in D, G1 and the cosines of its denominator; where V or L lies behind N_c
// the coat reflects nothing (Fc = 0 for V: the extension's |N_c.V| would reflect off a coat
// facing away). From behind, N_c is mirrored with the rest, its tangential part negated.
//
// fresnel_mix weighs the diffuse lobe by 1 - Fd(V.h) pair by pair, not by what the specular lobe
// takes from V, so the dielectric part is not energy-conserving at grazing views (a white,
// nearly smooth dielectric seen at N.V = 0.08 reflects 1.20); this is the specification's model,
// kept as it is, since glTF's viewers and exporters are made to match it.
//
// alpha = 0 (or alpha_c = 0) makes the specular lobes Dirac deltas: a mirror reflection of
// weight Fd and Fm (Fc) at V.h = N.V, and with transmission a straight passage of weight
// (1 - Fd) t c. Sampling picks a lobe with probability in proportion to its share of the light
// at N.V (the specular lobe's at least 2% of the base's), then a direction by the visible normals
// of GGX (the transmission lobe's mirrored) or the cosine.
#pragma once

#include "bsdfs/bsdf.h"

namespace wavetrace {

Color metallic_roughness_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf);
BsdfSample metallic_roughness_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1,
                                     float u2);

// What a clearcoat of weight k lets through of the light emitted beneath it towards V, for oc
// = N_c.V: 1 - k Fc, Fc as above (KHR_materials_clearcoat: the coat lies on top of the
// emission, "darkened by the Fresnel term"); 1 - k 0.04 seen head-on.
float coat_emission_weight(float clearcoat, float oc);

// Schlick's reflectance at normal incidence of a dielectric of index `ior`: ((ior - 1) /
// (ior + 1))^2, 0.04 at glTF's default 1.5.
inline float schlick_f0(float ior) {
    const float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

}  // namespace wavetrace
