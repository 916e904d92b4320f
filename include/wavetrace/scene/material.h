#pragma once

#include <cstdint>
#include <string>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/ids.h"

namespace wavetrace {

enum class MaterialKind : uint8_t {
    Lambertian,  // ideal diffuse: albedo / pi
    Metal,   // conductor with albedo and roughness in [0, 1] (Ray Tracing in One Weekend's "fuzz");
             // 0 is a mirror
    Mirror,  // perfect specular reflection tinted by albedo
    Dielectric,    // glass of index of refraction `ior`: smooth, or rough (alpha_u, alpha_v > 0)
    DiffuseLight,  // emits `emission` radiance from its front side (or both sides if `two_sided`)
    Isotropic,     // phase function of a participating medium; scattering albedo `albedo`
    Interface,     // no surface at all: a medium's boundary that rays cross unchanged
    Conductor,     // Fresnel of a complex index of refraction eta + i k, smooth or microfacet
};
inline constexpr int kMaterialKinds = int(MaterialKind::Conductor) + 1;

// The microfacet normal distributions of rough materials (shading/microfacet.h).
enum class Microfacet : uint8_t {
    Ggx,       // Trowbridge-Reitz (Walter et al. 2007)
    Beckmann,  // Beckmann-Spizzichino
};

const char* to_string(MaterialKind kind);

struct Material {
    std::string name;
    MaterialKind kind = MaterialKind::Lambertian;
    TextureId albedo = kNone;    // Lambertian, Metal, Mirror, Isotropic; Conductor: a factor on
                                 // the Fresnel reflectance (Mitsuba's specular_reflectance)
    float roughness = 0.0f;      // Metal
    float ior = 1.5f;            // Dielectric
    TextureId emission = kNone;  // DiffuseLight: radiance (W sr^-1 m^-2 per channel)
    bool two_sided = false;      // DiffuseLight: emits from both sides
    // Lambertian, Metal, Mirror, Conductor: reflects nothing from behind (Mitsuba's diffuse,
    // conductor, ...; its `twosided` wrapper is the default here).
    bool one_sided = false;
    // Conductor: the index of refraction eta + i k per channel, relative to the outside.
    // Conductor and Dielectric: the microfacet roughness along the shading frame's two tangents
    // (0, 0: smooth) and its distribution.
    Color eta{0.0f}, k{0.0f};
    Microfacet distribution = Microfacet::Ggx;
    float alpha_u = 0.0f, alpha_v = 0.0f;

    bool is_emissive() const { return kind == MaterialKind::DiffuseLight; }
};

}  // namespace wavetrace
