// What a material's textures give at a surface point, beyond its albedo: the weights of a
// principled material, the material a blend takes there, and whether any of its textures needs
// the point's uv at all.
#pragma once

#include <string>
#include <vector>

#include "bsdfs/bsdf.h"
#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/material.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

struct Scene;

// Whether any texture or map of m reads texture coordinates (a sphere's cost an acos and an
// atan2 to find); of a blend, its weight's or either material's.
bool material_reads_uv(const Scene& scene, const Material& m);

// The mesh attributes a hit on material m reads (some more than once): those of its albedo,
// metallic_roughness, alpha_u/alpha_v and opacity textures and, of a blend, its weight's and
// either material's. Its other textures may not read any (check_scene).
std::vector<std::string> material_attributes(const Scene& scene, MaterialId m);

// The field of m that reads a mesh attribute where none may be read (its emission, normal or
// bump map, its coat's textures, a principled weight: they are looked up where no triangle is
// known), or nullptr.
const char* attribute_misuse(const Scene& scene, const Material& m);

// The weights of a principled material m at texture coordinates uv and point p, into b (whose
// albedo is its base colour there): each a texture's luminance or a number, clamped to its
// range; the main lobes' GGX alphas and the clearcoat's GTR1 alpha from them.
void principled_at(const Scene& scene, const Material& m, Vec2 uv, Point3 p, BsdfParams* b);

// The textured factors of a metallic-roughness material m at texture point `at`, into b: glTF's
// channels, the metallicRoughnessTexture's green times `roughness` (alpha its square) and blue
// times `metallic`, the transmissionTexture's red times `transmission`, the clearcoatTexture's
// red times `clearcoat`, the clearcoatRoughnessTexture's green times `clearcoat_roughness` (the
// coat's alpha its square), each clamped to [0, 1].
void metallic_roughness_at(const Scene& scene,
                           const Material& m,
                           const TexturePoint& at,
                           BsdfParams* b);
// Its transmission's and coat's part alone, which the wavefront's light samples look up again
// from the vertex's uv and position (so these textures may not read mesh attributes:
// attribute_misuse).
void transmission_and_coat_at(const Scene& scene,
                              const Material& m,
                              const TexturePoint& at,
                              BsdfParams* b);

// What of a metallic-roughness material's emission leaves its surface at `at` towards wo (unit,
// on the side it is seen from) under its clearcoat: 1 - k Fc (coat_emission_weight), the coat's
// weight k and normal N_c at the point, N_c turned to wo's side as the BSDF mirrors it.
struct MappedPoint;
float emission_through_coat(const Scene& scene, const Material& m, const MappedPoint& at, Vec3 wo);

// The material a hit on material m takes at texture point `at`, u uniform in
// [0, 1): m itself unless it is a blend; a blend's second material where u < w (its weight
// there), else its first, and so on down nested blends, u rescaled at each choice to stay
// uniform over the part it fell in.
MaterialId blend_choice(const Scene& scene, MaterialId m, const TexturePoint& at, float u);

}  // namespace wavetrace
