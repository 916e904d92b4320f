// Plastic: a diffuse base of reflectance R (the albedo texture) under a dielectric coating of
// relative index of refraction eta, smooth or rough, as Mitsuba 3's `plastic` and
// `roughplastic` define it (its documentation, after Weidlich & Wilkie 2007, "Arbitrarily
// Layered Micro-Facet Surfaces"). Contract as bsdf.h states it: directions in the shading frame
// pointing away from the vertex; eval() includes cos theta_i; sample()'s weight is
// f cos / pdf. One side only, the front (wo.z > 0 and wi.z > 0); the material's one_sided rule
// (shading/path_vertex.h) decides, as for every opaque kind, whether the back is black or the
// front mirrored.
//
// Light crosses the coating into the base and out again, with the diffuse light that the
// coating reflects back in scattered again by the base:
//     R' = R / (1 - Fdr)      (linear, the default), or
//     R' = R / (1 - R Fdr)    (nonlinear: the geometric series of inner bounces, which
//                              darkens and saturates a coloured base)
// with Fdr the coating's internal diffuse reflectance.
//
// - Smooth: a delta reflection of weight S F(cos_o), and
//     f cos_i = R' (1 - F(cos_o)) (1 - F(cos_i)) / eta^2 * cos_i / pi,
//   F = fresnel_dielectric, Fdr = -1.440 / eta^2 + 0.710 / eta + 0.668 + 0.0636 eta (Egan and
//   Hilgeman's fit as Jensen et al. 2001, "A Practical Model for Subsurface Light Transport",
//   give it).
// - Rough (alpha > 0, isotropic): the coating's microfacet reflection with the separable Smith
//   masking-shadowing G1(o) G1(i) (Mitsuba's choice),
//     f cos_i = S F(o.h) D(h) G1(o) G1(i) / (4 cos_o),
//   plus R' T(cos_o) T(cos_i) / eta^2 * cos_i / pi, T = CoatingTable::transmittance (what the
//   coating's facets refract in and the surface does not mask), Fdr =
//   CoatingTable::internal_reflectance.
//
// S is the specular reflectance (1 by default). Sampling picks the specular lobe with
// probability P = E w / (E w + (1 - E)(1 - w)), E = F(cos_o) (smooth) or 1 - T(cos_o) (rough),
// w = the material's specular sampling weight (Mitsuba's: mean S / (mean S + mean R)); else a
// cosine-weighted direction. The rough specular lobe is sampled by visible normals of o.
#pragma once

#include "bsdfs/bsdf.h"
#include "wavetrace/bsdfs/coating.h"

namespace wavetrace {

Color plastic_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf);
BsdfSample plastic_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2);

// The smooth coating's Fdr above.
float plastic_internal_reflectance(float eta);

// The rough coating's table for a distribution, roughness alpha and eta (Mitsuba 3's
// definition): T(mu) = the mean over the visible normals m of a direction o of cosine mu of
// (1 - F(o.m)) G1(t), t the refraction of o at m, by quadrature; Fdr = 2 * the mean of
// mu R_in(mu) over the table's nodes, R_in the directional albedo of F D G1 G1 / (4 cos_o)
// seen from inside (relative index 1 / eta). T <= 1 - the albedo from outside: what the
// surface masks after refraction is lost (no multiple scattering), as in Mitsuba.
CoatingTable rough_coating_table(Microfacet distribution, float alpha, float eta);

}  // namespace wavetrace
