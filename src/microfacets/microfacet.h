// Microfacet normal distributions, GGX (Trowbridge-Reitz) and Beckmann, anisotropic with
// roughness alpha_u along the shading frame's x axis and alpha_v along its y, with Smith's
// masking and sampling of the visible normals. Directions are unit vectors in the shading frame
// (z along the normal), m a microfacet normal.
//
// The one-lane instances of the lane formulas in microfacet-inl.h (GGX's in ggx-inl.h,
// Beckmann's in beckmann-inl.h), in float: what the rough dielectric, plastic and the
// principled BSDFs evaluate in scalar code, and the rough conductor's lane formula
// (conductor-inl.h) in any number of lanes.
#pragma once

#include "wavetrace/math/vec3.h"
#include "wavetrace/microfacets/microfacet_kind.h"

namespace wavetrace {

struct MicrofacetDistribution {
    Microfacet kind = Microfacet::Ggx;
    float alpha_u = 0.0f, alpha_v = 0.0f;  // > 0

    // D(m): the density of microfacet normals per unit projected area, normalised so that
    // the integral of D(m) m.z over the hemisphere is 1; 0 for m.z <= 0.
    //   GGX:      1 / (pi au av (mx^2/au^2 + my^2/av^2 + mz^2)^2)           (Walter et al. 2007)
    //   Beckmann: exp(-(mx^2/au^2 + my^2/av^2) / mz^2) / (pi au av mz^4)
    float d(Vec3 m) const;
    // Smith's Lambda(w) (Heitz 2014, "Understanding the Masking-Shadowing Function", §5.1-5.2),
    // with a = w.z / sqrt(au^2 wx^2 + av^2 wy^2) = 1 / (alpha tan theta) along w's azimuth:
    //   GGX:      (-1 + sqrt(1 + 1 / a^2)) / 2
    //   Beckmann: (erf(a) - 1) / 2 + exp(-a^2) / (2 a sqrt(pi))
    float lambda(Vec3 w) const;
    // Smith's masking G1(w) = 1 / (1 + Lambda(w)) of the visible side, w.z > 0.
    float g1(Vec3 w) const;
    // The height-correlated masking-shadowing 1 / (1 + Lambda(wo) + Lambda(wi)) (Heitz 2014,
    // eq. 99), for wo, wi above the surface.
    float g2(Vec3 wo, Vec3 wi) const;
    // The density of visible normals from wo (wo.z > 0): G1(wo) max(0, wo.m) D(m) / wo.z
    // (Heitz 2014, eq. 16), per unit solid angle of m.
    float visible_pdf(Vec3 wo, Vec3 m) const;
    // A normal drawn with visible_pdf(wo, .), wo.z > 0: GGX by Heitz 2018 (JCGT 7(4)); Beckmann
    // by Heitz & d'Eon 2014 ("Importance Sampling Microfacet-Based BSDFs using the Distribution
    // of Visible Normals", EGSR): stretch wo to unit roughness, draw the slopes of the visible
    // normals there (the x slope by inverting its CDF, the y slope as a normal deviate),
    // rotate them to wo's azimuth and unstretch.
    Vec3 sample_visible(Vec3 wo, float u1, float u2) const;
};

}  // namespace wavetrace
