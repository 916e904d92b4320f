// Mitsuba 3's principled BSDFs, `principled` and `principledthin`: Burley's "Physically Based
// Shading at Disney" (SIGGRAPH 2012 course) and "Extending the Disney BRDF to a BSDF with
// Integrated Subsurface Scattering" (2015), in the form Mitsuba 3 documents and renders them, so
// that its scenes match its images. Contract as bsdf.h states it: directions in the shading
// frame pointing away from the vertex; eval() includes |cos theta_i|; sample()'s weight is
// f |cos| / pdf.
//
// Parameters (BsdfParams::principled, and albedo = c the base colour, eta the material's index
// of refraction, metallic m, transmission t = spec_trans, clearcoat k): the main lobes are GGX
// with alpha_x = max(0.001, r^2 / a), alpha_y = max(0.001, r^2 a), a = sqrt(1 - 0.9 aniso)
// (Burley 2012, B.2); with o the view, i the light direction, s(x) = (1 - |x|)^5 and
// Schlick(R0, x) = R0 + (1 - R0) s(x), F the exact dielectric Fresnel of eta at o.h:
//
// `principled`, o above the surface (front); brdf = (1 - m)(1 - t), bsdf = (1 - m) t:
//   diffuse     brdf c / pi [(1 - s(i)/2)(1 - s(o)/2) + R (s(i) + s(o) + s(i) s(o)(R - 1))]
//               with R = 2 r (h.i)^2 (Burley's retro-reflection), lerped towards the
//               Hanrahan-Krueger "flatness" lobe 1.25 (Fss (1 / (cos_i + cos_o) - 0.5) + 0.5)
//   sheen       sheen (1 - m) s(h.i) lerp(1, c / lum(c), sheen_tint)   (no 1 / pi, as Mitsuba)
//   specular    Fp D G / (4 cos_o cos_i), Fp = (1 - m)(1 - st) F + m Schlick(c, o.h)
//               + (1 - m) st Schlick(c / lum(c) R0(eta), o.h), st = spec_tint
//   transmission sqrt(c) bsdf (Walter et al. 2007's BTDF with F, radiance convention)
//   clearcoat   0.25 k Schlick(0.04, o.h) D1(h) G(0.25) — GTR1 with alpha lerp(0.1, 0.001,
//               clearcoat_gloss) and Smith GGX masking of alpha 0.25; Mitsuba's clearcoat
//               leaves out Burley's 1 / (4 cos_o cos_i), and so does this one.
//   From behind (o below) only the dielectric interface is left: bsdf F D G / (4 cos_o cos_i)
//   reflected, the transmission as in front; diffuse, sheen and clearcoat are front lobes.
//   D and G are GGX with Smith's separable masking of each direction against h, zero where a
//   direction sees the back of h.
// `principledthin` (thin): a sheet; both sides alike (o mirrored above the surface, i with it):
//   diffuse and sheen as above times (1 - t)(1 - d), d = diff_trans / 2 in [0, 1]
//   diffuse transmission (1 - t) d c / pi
//   specular    t lerp(F, Schlick(c / lum(c) R0(eta), o.h), spec_tint) D G / (4 cos_o cos_i)
//   transmission t c (1 - F) Ds G / (4 cos_o cos_i), i mirrored through the sheet (no
//               refraction), Ds of the roughness scaled by 0.65 eta - 0.35 (Burley 2015, fig. 15)
//
// Sampling: a lobe, then a direction from the GGX visible normals (specular, transmission), the
// GTR1 distribution (clearcoat) or the cosine (diffuse). `principled` picks the specular lobe,
// the clearcoat and the diffuse lobe in proportion to 1, k / 4 and brdf (Mitsuba's sampling
// weights), and within the specular lobe reflection or transmission in proportion to
// 1 - bsdf (1 - F) and bsdf (1 - F) at the sampled normal (F and bsdf (1 - F) from behind), so
// that pdf() is the density the sample was drawn with. `principledthin` picks its four lobes in
// proportion to t/2, t/2, (1 - t)(1 - d) and (1 - t) d, as Mitsuba does.
#pragma once

#include "bsdfs/bsdf.h"

namespace wavetrace {

Color principled_eval(const BsdfParams& b, Vec3 wo, Vec3 wi, float* pdf);
BsdfSample principled_sample(const BsdfParams& b, Vec3 wo, float u_lobe, float u1, float u2);

// The main lobes' GGX alphas from roughness r and anisotropy (Burley 2012, B.2): alpha_u along
// dp/du max(0.001, r^2 / a), alpha_v max(0.001, r^2 a), a = sqrt(1 - 0.9 anisotropic).
void principled_alphas(float roughness, float anisotropic, float* alpha_u, float* alpha_v);

// Mitsuba's index of refraction for a `specular` amount: 2 / (1 - sqrt(0.08 specular)) - 1,
// the inverse of specular = 12.5 ((eta - 1) / (eta + 1))^2 (0.5 gives 1.5).
float principled_eta_of_specular(float specular);

}  // namespace wavetrace
