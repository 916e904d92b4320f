// The kinds of scattering a material has: what bsdfs/ evaluates and samples, and what the scene's
// materials name.
#pragma once

#include <cstdint>

#include "wavetrace/microfacets/microfacet_kind.h"

namespace wavetrace {

enum class MaterialKind : uint8_t {
    Lambertian,  // ideal diffuse: albedo / pi
    Metal,   // conductor with albedo and roughness in [0, 1] (Ray Tracing in One Weekend's "fuzz");
             // 0 is a mirror
    Mirror,  // perfect specular reflection tinted by albedo
    Dielectric,      // glass of index of refraction `ior`: smooth, or rough (alpha_u, alpha_v > 0)
    DiffuseLight,    // emits `emission` radiance from its front side (or both sides if `two_sided`)
    Isotropic,       // phase function of a participating medium; scattering albedo `albedo`
    Interface,       // no surface at all: a medium's boundary that rays cross unchanged
    Conductor,       // Fresnel of a complex index of refraction eta + i k, smooth or microfacet
    Plastic,         // a diffuse base under a dielectric coating, smooth or rough (Mitsuba 3's
                     // plastic and roughplastic)
    ThinDielectric,  // a sheet of glass of index `ior`: reflects, or passes light straight on
    MetallicRoughness,  // glTF 2.0's metallic-roughness material, with its transmission and
                        // clearcoat extensions
    Principled,         // Mitsuba 3's principled BSDF (Burley's Disney BSDF), or its thin sheet
    Blend,  // one of two materials at each hit (Mitsuba 3's blendbsdf, pbrt-v4's mix): chosen
            // where the hit is found (shading/surface.h), so no BSDF of this kind is evaluated
};
inline constexpr int kMaterialKinds = int(MaterialKind::Blend) + 1;

}  // namespace wavetrace
