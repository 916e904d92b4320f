// What Assimp 5.2 does not read from a glTF 2.0 file, or reads in ways of its own, read from the
// file's JSON beside Assimp: emissive strengths, and the cameras and punctual lights the node
// hierarchy places (glTF 2.0 specification, "Cameras", "Transformations"; KHR_lights_punctual).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "formats/json_reader.h"
#include "wavetrace/math/vec3.h"

namespace wavetrace {

// How deep glTF nodes may nest: Assimp walks the hierarchy recursively.
inline constexpr int kMaxGltfNodeDepth = 1024;

// What must hold before Assimp reads a glTF 2.0 file (`binary`: a .glb), which it cannot take
// otherwise: a .glb's header length within the file and every chunk within that length
// (Assimp allocates a chunk's claimed length before reading it); JSON nested at most
// json_reader::kMaxNesting deep, and a node hierarchy without cycles or shared children at
// most kMaxGltfNodeDepth deep (Assimp recurses through both and overflows its stack). Returns
// the parsed JSON; throws std::runtime_error (without the path).
json_reader::Document check_gltf(const std::filesystem::path& path, bool binary);

// Per material of the file's JSON `doc` (as check_gltf returns it), in the file's order
// (Assimp's too): KHR_materials_emissive_strength's emissiveStrength, 1 where the material does
// not give one. Throws std::runtime_error for a strength that is negative or not finite.
std::vector<float> gltf_emissive_strengths(const json_reader::json& doc);

// Per material of `doc`, in the file's order: the extensions it uses that wavetrace does not
// read, each named once in the order met (a material's own but KHR_materials_emissive_strength,
// _ior, _transmission and _clearcoat, e.g. KHR_materials_sheen; its textures' but
// KHR_texture_transform), so that none is dropped without a word.
std::vector<std::vector<std::string>> gltf_unread_material_extensions(const json_reader::json& doc);

// A texture's KHR_texture_transform: in glTF's uv space (v down the image),
// uv' = offset + [[cos r, sin r], [-sin r, cos r]] (scale * uv), and the uv set the texture
// reads (TEXCOORD_n: the transform's texCoord, else the textureInfo's, else 0).
struct GltfUvTransform {
    float offset[2] = {0, 0};
    float rotation = 0;  // radians
    float scale[2] = {1, 1};
    int tex_coord = 0;
};
// Per material of `doc`, in the file's order: the transform of each of its textures that has
// one or reads a uv set other than the first (then the identity), with the texture's key
// ("baseColorTexture", "clearcoatNormalTexture", ...). Throws std::runtime_error, naming the
// JSON pointer, for a value that is not a finite number or a texCoord that is not an index.
std::vector<std::vector<std::pair<std::string, GltfUvTransform>>> gltf_texture_transforms(
    const json_reader::json& doc);

// A perspective or orthographic camera where a node puts it, in world space: glTF cameras look
// along their node's -z with +y up.
struct GltfCamera {
    std::string name;        // the camera's, else its node's
    std::string pointer;     // JSON pointer of the node, for messages
    Point3 position;
    Vec3 forward, up;        // unit
    float yfov_degrees = 0;  // perspective: vertical field of view
    float aspect = 0;        // width / height; 0: not given
    bool orthographic = false;
    float view_width = 0, view_height = 0;  // orthographic: 2 xmag, 2 ymag
};

// A KHR_lights_punctual light where a node puts it, in world space.
struct GltfLight {
    enum class Kind { Point, Spot, Directional } kind = Kind::Point;
    std::string pointer;  // JSON pointer of the light, for messages
    Point3 position;
    Vec3 direction{0, 0, -1};  // where the light travels (spot, directional): the node's -z
    Color color{1.0f};         // color times intensity (candela; lux for directional)
    float inner_degrees = 0, outer_degrees = 45;  // spot cone
    bool has_range = false;
};

struct GltfPlacements {
    std::vector<GltfCamera> cameras;  // in the order the default scene's nodes meet them
    std::vector<GltfLight> lights;
    std::vector<std::string> warnings;  // what is not represented (orthographic cameras, ...)
};

// The cameras and lights of the file's default scene (`scene`, else scene 0, else none),
// walking its nodes with their matrix or translation, rotation (unit quaternion x, y, z, w)
// and scale. Throws std::runtime_error for a malformed hierarchy (an index out of range, a
// cycle, nesting deeper than 1024) or values out of range.
GltfPlacements gltf_placements(const std::filesystem::path& path, bool binary);

}  // namespace wavetrace
