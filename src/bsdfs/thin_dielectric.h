// The thin dielectric: a sheet of glass of relative index of refraction eta too thin to offset
// the light (a window pane, a soap film), as Mitsuba 3's `thindielectric` and pbrt-v4's
// `thindielectric` model it. Contract as bsdf.h states it; both lobes are Dirac deltas, so
// eval and pdf are 0 and sample() returns the lobe's throughput.
//
// Light bounces back and forth between the sheet's two faces: with R = F(|cos theta|, eta) at
// one face (fresnel_dielectric) and T = 1 - R, the sheet reflects R' = R + T^2 R / (1 - R^2)
// (the geometric series of the inner bounces) and transmits T' = 1 - R', straight on (the two
// refractions cancel). sample() reflects with probability R' and passes through otherwise,
// each with weight 1; both sides alike.
#pragma once

#include "bsdfs/bsdf.h"

namespace wavetrace {

// R' above, for |cos theta| = cos_i.
float thin_dielectric_reflectance(float cos_i, float eta);
BsdfSample thin_dielectric_sample(const BsdfParams& b, Vec3 wo, float u_lobe);

}  // namespace wavetrace
