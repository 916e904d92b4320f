#pragma once

#include <cstdint>
#include <string>

#include "wavetrace/scene/ids.h"

namespace wavetrace {

enum class MaterialKind : uint8_t {
    Lambertian,  // ideal diffuse: albedo / pi
    Metal,       // conductor with albedo and roughness in [0, 1] (Ray Tracing in One Weekend's "fuzz"); 0 is a mirror
    Mirror,      // perfect specular reflection tinted by albedo
    Dielectric,  // smooth glass with index of refraction `ior`
    DiffuseLight,  // emits `emission` radiance from its front side (or both sides if `two_sided`)
    Isotropic,     // phase function of a participating medium; scattering albedo `albedo`
    Interface,     // no surface at all: a medium's boundary that rays cross unchanged
};

const char* to_string(MaterialKind kind);

struct Material {
    std::string name;
    MaterialKind kind = MaterialKind::Lambertian;
    TextureId albedo = kNone;    // Lambertian, Metal, Mirror, Isotropic
    float roughness = 0.0f;      // Metal
    float ior = 1.5f;            // Dielectric
    TextureId emission = kNone;  // DiffuseLight: radiance (W sr^-1 m^-2 per channel)
    bool two_sided = false;      // DiffuseLight

    bool is_emissive() const { return kind == MaterialKind::DiffuseLight; }
};

}  // namespace wavetrace
