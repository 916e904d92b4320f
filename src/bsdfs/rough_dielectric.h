// The rough dielectric: reflection and refraction by a microfacet interface between the
// outside (the shape's front) and an inside of relative index of refraction eta (Walter,
// Marschner, Li and Torrance 2007, "Microfacet Models for Refraction through Rough Surfaces").
// Contract as bsdf.h states it: directions in the shading frame pointing away from the vertex,
// eval() includes |cos theta_i|, sample()'s weight is f |cos| / pdf.
//
// With eta the index of wi's side over wo's (ior entering from the front, 1 / ior from behind):
// - reflection, h = normalize(wo + wi) on wo's side:
//     f cos_i = F(wo.h) D(h) G2 / (4 |cos_o|)
// - transmission, h = -normalize(eta wi + wo) turned to wo's side (eq. 16):
//     f cos_i = |wi.h| |wo.h| (1 - F(wo.h)) D(h) G2 / (|cos_o| (eta wi.h + wo.h)^2)   (eq. 21,
//   for radiance: the Jacobian of eq. 17 makes a sample's weight carry 1 / eta^2, as the smooth
//   dielectric's refraction does)
// G2 is the height-correlated 1 / (1 + Lambda(wo) + Lambda(wi)) in both cases (pbrt-v4's
// choice), F fresnel_dielectric. Sampling: a visible normal m of wo, then reflection with
// probability F(wo.m), refraction otherwise; pdf = D_wo(h) times F / (4 |wo.h|) or
// (1 - F) eta^2 |wi.h| / (eta wi.h + wo.h)^2. Both sides are rough alike.
#pragma once

#include "bsdfs/bsdf.h"

namespace wavetrace {

Color rough_dielectric_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf);
BsdfSample rough_dielectric_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2);

}  // namespace wavetrace
