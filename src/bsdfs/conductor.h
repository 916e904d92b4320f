// The conductor: reflection by a metal of complex index of refraction eta + i k (per RGB
// channel, relative to the outside), smooth or rough. Contract, as bsdf.h states it for every
// kind: directions in the shading frame pointing away from the vertex; eval() includes
// |cos theta_i|; sample()'s weight is f |cos| / pdf.
//
// - Smooth (alpha_u = alpha_v = 0): a mirror, weight R F(|cos theta_o|), a delta lobe
//   (specular-inl.h, which bsdf_sample runs; conductor_sample takes the rough lobe only).
// - Rough: Cook-Torrance with the microfacet distribution (Walter et al. 2007, "Microfacet
//   Models for Refraction through Rough Surfaces", eq. 20):
//   f cos_i = R F(o.h) D(h) G2(o, i) / (4 cos_o), h = (o + i) / |o + i|, sampled by the
//   visible normals of o, pdf = G1(o) D(h) / (4 cos_o), weight = R F(o.h) G2 / G1(o).
// R is the reflectance texture's value (Mitsuba's specular_reflectance, 1 by default), F
// fresnel_conductor. The rough lobe is the one-lane instance of conductor-inl.h's lane
// formula. Both sides reflect: from behind (wo.z < 0) the lobe is mirrored
// below the surface, as for `metal`; wo and wi on opposite sides give 0.
#pragma once

#include "bsdfs/bsdf.h"

namespace wavetrace {

Color conductor_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf);
BsdfSample conductor_sample(const BsdfParams& b, Vec3 wo, float u1, float u2);

}  // namespace wavetrace
