// Which BSDFs the lane formulas take (the -inl.h lobes over SIMD lanes: diffuse, metal,
// conductor, dielectric, metallic-roughness, specular, glossy), and as which lobe: the rule both
// engines follow (shading/lane_routes.h), so that a vertex takes the same formula in each.
#pragma once

#include <cstdint>

#include "bsdfs/bsdf.h"
#include "wavetrace/bsdfs/material_kind.h"

namespace wavetrace {

// Whether the lane formulas take the surface BSDF b: Lambertian, a mirror, a metal, an isotropic
// conductor or dielectric (smooth: a Dirac-delta lobe, specular-inl.h; rough: a glossy lobe), or
// a metallic-roughness surface whose lobes are all rough and whose coat lies along the shading
// normal. They build the shading frame from the normal alone, which an isotropic BSDF allows.
inline bool is_lane_bsdf(const BsdfParams& b) {
    switch (b.kind) {
        case MaterialKind::Lambertian:
        case MaterialKind::Mirror:
        case MaterialKind::Metal:
            return true;
        case MaterialKind::Conductor:
        case MaterialKind::Dielectric:
            return b.alpha_v == b.alpha;
        case MaterialKind::MetallicRoughness:
            return b.alpha > 0.0f && b.alpha_v == b.alpha &&
                   (b.clearcoat == 0.0f || (b.clearcoat_alpha > 0.0f && b.coat_along_normal()));
        default:
            return false;
    }
}

// The index of refraction the lane formulas read (LaneBsdf::eta): a conductor's eta, a
// dielectric's index in every channel.
inline Color lane_eta(const BsdfParams& b) {
    return b.kind == MaterialKind::Dielectric ? Color(b.eta) : b.conductor_eta;
}

// The lobes of the BSDFs the lane formulas take (is_lane_bsdf), as int32 rows of the
// wavefront's lane blocks (blocks/lane_kernels.h).
enum class LaneLobe : int32_t {
    Lambertian,
    RoughMetal,
    RoughConductor,
    RoughDielectric,
    MetallicRoughness,
    Phase,
    Specular,  // a Dirac-delta lobe: a mirror, a smooth metal, conductor or dielectric
};
inline LaneLobe lane_lobe(MaterialKind kind) {
    switch (kind) {
        case MaterialKind::Metal:
            return LaneLobe::RoughMetal;
        case MaterialKind::Conductor:
            return LaneLobe::RoughConductor;
        case MaterialKind::Dielectric:
            return LaneLobe::RoughDielectric;
        case MaterialKind::MetallicRoughness:
            return LaneLobe::MetallicRoughness;
        case MaterialKind::Isotropic:
            return LaneLobe::Phase;
        default:
            return LaneLobe::Lambertian;
    }
}
// The lobe of a lane BSDF b (is_lane_bsdf).
inline LaneLobe lane_lobe(const BsdfParams& b) {
    return b.is_delta() ? LaneLobe::Specular : lane_lobe(b.kind);
}
// The kind a lobe's light samples are queued as (a Specular row takes none).
inline MaterialKind material_kind(LaneLobe lobe) {
    switch (lobe) {
        case LaneLobe::RoughMetal:
            return MaterialKind::Metal;
        case LaneLobe::RoughConductor:
            return MaterialKind::Conductor;
        case LaneLobe::RoughDielectric:
            return MaterialKind::Dielectric;
        case LaneLobe::MetallicRoughness:
            return MaterialKind::MetallicRoughness;
        case LaneLobe::Phase:
            return MaterialKind::Isotropic;
        default:
            return MaterialKind::Lambertian;
    }
}

}  // namespace wavetrace
