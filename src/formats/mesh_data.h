// What a mesh file holds once read, as the file states it: triangles, their materials and the
// images inside the file. The readers of the formats fill it (formats/ply_mesh.h,
// formats/serialized_mesh.h; loaders/mesh_file.h through Assimp).
#pragma once

#include <string>
#include <vector>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/shapes.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

// A material as the file states it (OBJ's MTL keys; other formats fill what they have).
// Mapping it onto wavetrace's materials is the scene loader's business.
struct FileMaterial {
    std::string name;
    Color kd{0.0f}, ks{0.0f}, ke{0.0f};
    float ns = 0.0f;        // Phong exponent
    float ni = 1.0f;        // index of refraction
    int illum = -1;         // OBJ illumination model; -1: not given
    float dissolve = 1.0f;  // d: 1 is opaque
    std::string map_kd;     // diffuse texture path as written, relative to the file's folder
    std::vector<std::string> other_maps;  // texture kinds that cannot be mapped (e.g. "map_Bump")

    // glTF 2.0 files (pbr): the metallic-roughness material. kd is the base colour factor,
    // map_kd its texture, ke the emissive factor times KHR_materials_emissive_strength, ni the ior
    // (KHR_materials_ior; 1.5 if not given); the factors of pbrMetallicRoughness,
    // KHR_materials_transmission and _clearcoat; the metallicRoughness, normal, emissive,
    // clearcoat and clearcoatRoughness textures; alphaMode, its cutoff, doubleSided.
    bool pbr = false;
    float metallic = 1.0f, roughness = 1.0f, transmission = 0.0f, clearcoat = 0.0f,
          clearcoat_roughness = 0.0f;
    std::string map_metallic_roughness, map_normal, map_emissive, map_transmission, map_clearcoat,
        map_clearcoat_roughness, map_clearcoat_normal;
    // Each texture's glTF sampler: wrapS, wrapT, and magFilter (no mip maps here: minFilter
    // has nothing to choose between).
    struct Sampler {
        TextureWrap wrap_u = TextureWrap::Repeat, wrap_v = TextureWrap::Repeat;
        TextureFilter filter = TextureFilter::Bilinear;
        // KHR_texture_transform in the mesh's uv space, as Texture::uv.
        float uv[2][3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    };
    Sampler kd_sampler, metallic_roughness_sampler, normal_sampler, emissive_sampler,
        transmission_sampler, clearcoat_sampler, clearcoat_roughness_sampler,
        clearcoat_normal_sampler;
    std::string alpha_mode = "OPAQUE";
    float base_alpha = 1.0f, alpha_cutoff = 0.5f;  // baseColorFactor's alpha; MASK's cutoff
    bool double_sided = false;
};

// The triangles [first_triangle, first_triangle + triangles) use material `material`.
struct MeshPart {
    size_t first_triangle = 0, triangles = 0;
    uint32_t material = 0;  // index into MeshFile::materials
};

// An image held inside the mesh file (a .glb's buffer, a data URI), encoded as `format` says
// ("png", "jpg"); materials name it "*N", N its index.
struct EmbeddedImage {
    std::vector<unsigned char> bytes;
    std::string format;
};

// A triangle mesh as read from a file: every mesh in the file merged, node transforms applied.
struct MeshFile {
    std::vector<Point3> positions;
    std::vector<Normal3> normals;   // empty, or one per position
    std::vector<Vec2> uvs;          // empty, or one per position
    std::vector<uint32_t> indices;  // three per triangle
    std::vector<FileMaterial> materials;
    std::vector<MeshPart> parts;  // in triangle order, covering every triangle
    std::vector<EmbeddedImage> embedded;
    // Per-vertex and per-triangle values beyond the geometry (a PLY's further properties).
    std::vector<MeshAttribute> attributes;
    // Files the mesh names that are not there ("names x.mtl: no such file"): Assimp carries on
    // without them.
    std::vector<std::string> warnings;
};

}  // namespace wavetrace
