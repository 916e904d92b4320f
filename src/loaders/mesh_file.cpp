#include "loaders/mesh_file.h"

#include <assimp/BaseImporter.h>
#include <assimp/GltfMaterial.h>
#include <assimp/ObjMaterial.h>
#include <assimp/importerdesc.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "files/input_file.h"
#include "formats/gltf_json.h"
#include "formats/mesh_guards.h"
#include "formats/ply_mesh.h"
#include "loaders/mesh_io.h"

namespace wavetrace {
namespace {

// Assimp reads a file with the reader of its extension; where several readers share one
// (.gltf: glTF 1 and glTF 2) and none recognises the content, it falls back to trying every
// reader on the content, which handed a broken PLY named .gltf to the PLY reader, where it
// hung (found by tests/fuzz/fuzz_mesh). Such files are refused here instead.
void refuse_unrecognised(const Assimp::Importer& importer,
                         const std::filesystem::path& path,
                         const std::string& extension) {
    std::vector<size_t> readers;
    for (size_t i = 0; i < importer.GetImporterCount(); ++i) {
        std::istringstream list(importer.GetImporterInfo(i)->mFileExtensions);
        for (std::string e; list >> e;)
            if (e == extension) readers.push_back(i);
    }
    if (readers.size() <= 1) return;  // one reader: Assimp uses it, with no fallback
    for (size_t i : readers)
        if (importer.GetImporter(i)->CanRead(path.string(), importer.GetIOHandler(), false)) return;
    throw std::runtime_error("not a ." + extension + " file that its readers recognise");
}

// Assimp catches what its readers throw and keeps only the message: running out of memory
// becomes the error string "std::bad_alloc", which is rethrown as what it was.
[[noreturn]] void import_failed(const Assimp::Importer& importer) {
    const std::string why = importer.GetErrorString();
    if (why == std::bad_alloc().what()) throw std::bad_alloc();
    throw std::runtime_error(why);
}

Color color_of(const aiMaterial& m, const char* key, unsigned type, unsigned index) {
    aiColor3D c(0, 0, 0);
    m.Get(key, type, index, c);
    return {c.r, c.g, c.b};
}

std::string texture_path(const aiMaterial& m, aiTextureType type, unsigned index = 0) {
    aiString path;
    if (m.GetTextureCount(type) > index && m.GetTexture(type, index, &path) == AI_SUCCESS)
        return path.C_Str();
    return {};
}

// A texture's glTF sampler as Assimp 5.2's glTF 2.0 reader stores it beside the texture:
// wrapS and wrapT as aiTextureMapMode, magFilter as glTF's enum (9728 NEAREST, 9729 LINEAR),
// absent where the file gives none (glTF's defaults: REPEAT; the filter is ours to choose).
FileMaterial::Sampler texture_sampler(const aiMaterial& m, aiTextureType type, unsigned index) {
    FileMaterial::Sampler s;
    auto wrap = [](int mode) {
        switch (mode) {
            case aiTextureMapMode_Clamp: return TextureWrap::Clamp;
            case aiTextureMapMode_Mirror: return TextureWrap::Mirror;
            default: return TextureWrap::Repeat;
        }
    };
    int mode = 0;
    if (m.Get(AI_MATKEY_MAPPINGMODE_U(type, index), mode) == AI_SUCCESS) s.wrap_u = wrap(mode);
    if (m.Get(AI_MATKEY_MAPPINGMODE_V(type, index), mode) == AI_SUCCESS) s.wrap_v = wrap(mode);
    int mag = 0;
    if (m.Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, index), mag) == AI_SUCCESS && mag == 9728)
        s.filter = TextureFilter::Nearest;
    return s;
}

// glTF's metallic-roughness material as Assimp 5.2's glTF 2.0 reader stores it: the base colour
// factor under $clr.base, the metallicRoughness texture as texture type UNKNOWN, the extensions'
// factors under their keys, the ior (KHR_materials_ior) as the refractive index.
void read_gltf_material(const aiMaterial& m, FileMaterial& out) {
    out.pbr = true;
    aiColor4D base(1, 1, 1, 1);  // the specification's default material is white
    m.Get(AI_MATKEY_BASE_COLOR, base);
    out.kd = {base.r, base.g, base.b};
    out.base_alpha = base.a;
    m.Get(AI_MATKEY_GLTF_ALPHACUTOFF, out.alpha_cutoff);
    out.ni = 1.5f;
    m.Get(AI_MATKEY_REFRACTI, out.ni);
    m.Get(AI_MATKEY_METALLIC_FACTOR, out.metallic);
    m.Get(AI_MATKEY_ROUGHNESS_FACTOR, out.roughness);
    m.Get(AI_MATKEY_TRANSMISSION_FACTOR, out.transmission);
    m.Get(AI_MATKEY_CLEARCOAT_FACTOR, out.clearcoat);
    m.Get(AI_MATKEY_CLEARCOAT_ROUGHNESS_FACTOR, out.clearcoat_roughness);
    aiString mode;
    if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, mode) == AI_SUCCESS) out.alpha_mode = mode.C_Str();
    int two_sided = 0;
    if (m.Get(AI_MATKEY_TWOSIDED, two_sided) == AI_SUCCESS) out.double_sided = two_sided != 0;
    out.map_kd = texture_path(m, aiTextureType_BASE_COLOR);
    out.kd_sampler = texture_sampler(m, aiTextureType_BASE_COLOR, 0);
    if (out.map_kd.empty()) {
        out.map_kd = texture_path(m, aiTextureType_DIFFUSE);
        out.kd_sampler = texture_sampler(m, aiTextureType_DIFFUSE, 0);
    }
    out.map_metallic_roughness =
        texture_path(m, AI_MATKEY_GLTF_PBRMETALLICROUGHNESS_METALLICROUGHNESS_TEXTURE);
    out.metallic_roughness_sampler =
        texture_sampler(m, AI_MATKEY_GLTF_PBRMETALLICROUGHNESS_METALLICROUGHNESS_TEXTURE);
    out.map_normal = texture_path(m, aiTextureType_NORMALS);
    out.normal_sampler = texture_sampler(m, aiTextureType_NORMALS, 0);
    out.map_emissive = texture_path(m, aiTextureType_EMISSIVE);
    out.emissive_sampler = texture_sampler(m, aiTextureType_EMISSIVE, 0);
    out.map_transmission = texture_path(m, AI_MATKEY_TRANSMISSION_TEXTURE);
    out.transmission_sampler = texture_sampler(m, AI_MATKEY_TRANSMISSION_TEXTURE);
    out.map_clearcoat = texture_path(m, AI_MATKEY_CLEARCOAT_TEXTURE);
    out.clearcoat_sampler = texture_sampler(m, AI_MATKEY_CLEARCOAT_TEXTURE);
    out.map_clearcoat_roughness = texture_path(m, AI_MATKEY_CLEARCOAT_ROUGHNESS_TEXTURE);
    out.clearcoat_roughness_sampler = texture_sampler(m, AI_MATKEY_CLEARCOAT_ROUGHNESS_TEXTURE);
    out.map_clearcoat_normal = texture_path(m, AI_MATKEY_CLEARCOAT_NORMAL_TEXTURE);
    out.clearcoat_normal_sampler = texture_sampler(m, AI_MATKEY_CLEARCOAT_NORMAL_TEXTURE);
    // (Extensions that are not read, KHR_materials_sheen's textures among them, are named from
    // the file's JSON: gltf_unread_material_extensions.)
    const std::pair<aiTextureType, const char*> others[] = {
        {aiTextureType_AMBIENT_OCCLUSION, "occlusionTexture"},
        {aiTextureType_LIGHTMAP, "occlusionTexture"}};
    for (const auto& [type, key] : others)
        if (m.GetTextureCount(type) > 0 &&
            std::find(out.other_maps.begin(), out.other_maps.end(), key) == out.other_maps.end())
            out.other_maps.push_back(key);
}

// The texture of glTF key `key` (e.g. "baseColorTexture") moved by KHR_texture_transform t.
// Assimp flips glTF's v (v down the image) to 1 - v, so in the mesh's uv space the transform
// uv' = o + M uv, M = [[a, b], [c, d]] = R(r) S, becomes [[a, -b, b + o_u], [-c, d, 1 - d - o_v]].
// A texture that reads another uv set (texCoord) is named: only the first is imported, and
// the texture reads that.
void apply_uv_transform(FileMaterial& fm, const std::string& key, const GltfUvTransform& t) {
    FileMaterial::Sampler* s = key == "baseColorTexture"           ? &fm.kd_sampler
                               : key == "metallicRoughnessTexture" ? &fm.metallic_roughness_sampler
                               : key == "normalTexture"            ? &fm.normal_sampler
                               : key == "emissiveTexture"          ? &fm.emissive_sampler
                               : key == "transmissionTexture"      ? &fm.transmission_sampler
                               : key == "clearcoatTexture"         ? &fm.clearcoat_sampler
                               : key == "clearcoatRoughnessTexture"
                                   ? &fm.clearcoat_roughness_sampler
                               : key == "clearcoatNormalTexture" ? &fm.clearcoat_normal_sampler
                                                                 : nullptr;
    if (!s) return;  // a texture that is not read (warned about as such)
    if (t.tex_coord > 0)
        fm.other_maps.push_back(key + "'s texCoord " + std::to_string(t.tex_coord) +
                                " (read from TEXCOORD_0: no other uv set is imported)");
    const float c = std::cos(t.rotation), sn = std::sin(t.rotation);
    const float a = c * t.scale[0], b = sn * t.scale[1], cc = -sn * t.scale[0], d = c * t.scale[1];
    s->uv[0][0] = a;
    s->uv[0][1] = -b;
    s->uv[0][2] = b + t.offset[0];
    s->uv[1][0] = -cc;
    s->uv[1][1] = d;
    s->uv[1][2] = 1.0f - d - t.offset[1];
}

FileMaterial read_material(const aiMaterial& m, bool gltf) {
    FileMaterial out;
    aiString name;
    if (m.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) out.name = name.C_Str();
    out.kd = color_of(m, AI_MATKEY_COLOR_DIFFUSE);
    out.ks = color_of(m, AI_MATKEY_COLOR_SPECULAR);
    out.ke = color_of(m, AI_MATKEY_COLOR_EMISSIVE);
    m.Get(AI_MATKEY_SHININESS, out.ns);
    m.Get(AI_MATKEY_REFRACTI, out.ni);
    m.Get(AI_MATKEY_OPACITY, out.dissolve);
    int illum = -1;
    if (m.Get(AI_MATKEY_OBJ_ILLUM, illum) == AI_SUCCESS) out.illum = illum;
    if (gltf) {
        read_gltf_material(m, out);
        return out;
    }
    out.map_kd = texture_path(m, aiTextureType_DIFFUSE);
    const std::pair<aiTextureType, const char*> others[] = {
        {aiTextureType_SPECULAR, "map_Ks"}, {aiTextureType_AMBIENT, "map_Ka"},
        {aiTextureType_EMISSIVE, "map_Ke"}, {aiTextureType_HEIGHT, "map_Bump"},
        {aiTextureType_NORMALS, "norm"},    {aiTextureType_SHININESS, "map_Ns"},
        {aiTextureType_OPACITY, "map_d"},   {aiTextureType_DISPLACEMENT, "disp"},
        {aiTextureType_REFLECTION, "refl"}};
    for (const auto& [type, key] : others)
        if (m.GetTextureCount(type) > 0) out.other_maps.push_back(key);
    return out;
}

}  // namespace

MeshFile read_mesh_file(const std::filesystem::path& path,
                        const std::filesystem::path& asset_root) {
    check_input_file(path, kMaxMeshFileBytes, "meshes");
    std::string lower = path.extension().string();
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower == ".ply") return read_ply_mesh(path);
    Assimp::Importer importer;
    auto* io = new MeshIO(path, asset_root);
    importer.SetIOHandler(io);  // the importer owns it
    std::string ext = path.extension().string();
    if (ext.empty() || !importer.IsExtensionSupported(ext))
        throw std::runtime_error("unsupported mesh format '" + ext +
                                 "' (Assimp reads e.g. .obj, .ply, .gltf, .glb, .stl)");
    lower = lower.substr(1);
    if (lower == "off") check_off(path);
    if (lower == "obj") check_obj(path);
    const bool gltf = lower == "gltf" || lower == "glb";
    const json_reader::Document gltf_doc =
        gltf ? check_gltf(path, lower == "glb") : json_reader::Document();
    refuse_unrecognised(importer, path, lower);
    // Keep only triangles. Assimp's OBJ reader un-indexes faces; joining identical vertices
    // restores the shared indexing (and the memory) of the file.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    // Read and validate first, check the faces ourselves, and only then post-process:
    // Assimp's post-processing steps assert (abort the process) on faces that its readers let
    // through, e.g. a binary PLY face with no indices (found by tests/fuzz/fuzz_mesh).
    const aiScene* scene = importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
    // A file it refused to open is the error, whatever Assimp made of its absence.
    if (!io->refused().empty()) throw std::runtime_error(io->refused().front());
    if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
        if (!io->missing().empty()) throw std::runtime_error(io->missing().front());
        import_failed(importer);
    }
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices == 0 || !face.mIndices)
                throw std::runtime_error("face " + std::to_string(f) + " of mesh " +
                                         std::to_string(m) + " has no vertices");
            for (unsigned k = 0; k < face.mNumIndices; ++k)
                if (face.mIndices[k] >= mesh->mNumVertices)
                    throw std::runtime_error("face " + std::to_string(f) + " of mesh " +
                                             std::to_string(m) + " uses vertex " +
                                             std::to_string(face.mIndices[k]) + " of " +
                                             std::to_string(mesh->mNumVertices));
        }
    }
    scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                         aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
    if (!scene || !scene->mRootNode) import_failed(importer);

    MeshFile out;
    // Assimp looks for a missing file under several names: the first is the file's own.
    if (!io->missing().empty()) out.warnings.push_back("names " + io->missing().front());
    for (unsigned m = 0; m < scene->mNumMaterials; ++m)
        out.materials.push_back(read_material(*scene->mMaterials[m], gltf));
    if (gltf) {
        // Assimp keeps the file's materials in order (appending a default one at most).
        const std::vector<float> strengths = gltf_emissive_strengths(gltf_doc.root);
        for (size_t m = 0; m < strengths.size() && m < out.materials.size(); ++m)
            out.materials[m].ke *= strengths[m];
        const auto transforms = gltf_texture_transforms(gltf_doc.root);
        for (size_t m = 0; m < transforms.size() && m < out.materials.size(); ++m)
            for (const auto& [key, t] : transforms[m]) apply_uv_transform(out.materials[m], key, t);
        const auto unread = gltf_unread_material_extensions(gltf_doc.root);
        for (size_t m = 0; m < unread.size() && m < out.materials.size(); ++m)
            for (const std::string& name : unread[m]) out.materials[m].other_maps.push_back(name);
    }
    if (out.materials.empty()) out.materials.push_back(FileMaterial{"(none)"});
    for (unsigned t = 0; t < scene->mNumTextures; ++t) {
        const aiTexture& tex = *scene->mTextures[t];
        EmbeddedImage image;
        if (tex.mHeight == 0 && tex.pcData) {  // compressed: mWidth bytes of a png, jpg, ...
            const auto* bytes = reinterpret_cast<const unsigned char*>(tex.pcData);
            image.bytes.assign(bytes, bytes + tex.mWidth);
            image.format = tex.achFormatHint;
        }
        out.embedded.push_back(std::move(image));
    }
    bool all_normals = true, all_uvs = true, any_colors = false, any_alpha = false;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        all_normals = all_normals && mesh->HasNormals();
        all_uvs = all_uvs && mesh->HasTextureCoords(0);
        if (!mesh->HasVertexColors(0)) continue;
        any_colors = true;
        for (unsigned v = 0; gltf && v < mesh->mNumVertices && !any_alpha; ++v)
            any_alpha = mesh->mColors[0][v].a != 1.0f;
    }
    // Vertex colours (glTF's COLOR_0, an OBJ's `v x y z r g b`) are the `vertex_color`
    // attribute, white where a mesh of the file has none (glTF's default); a glTF material
    // multiplies its base colour and alpha by them (glTF 2.0, 3.7.2.1), so there the alpha is
    // `vertex_alpha`, where some vertex is not opaque.
    if (any_colors) out.attributes.push_back({"vertex_color", false, 3, {}});
    if (gltf && any_alpha) out.attributes.push_back({"vertex_alpha", false, 1, {}});
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        uint32_t base = static_cast<uint32_t>(out.positions.size());
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            const aiVector3D& p = mesh->mVertices[v];
            out.positions.push_back({p.x, p.y, p.z});
            if (all_normals) {
                const aiVector3D& n = mesh->mNormals[v];
                out.normals.push_back({n.x, n.y, n.z});
            }
            if (all_uvs) {
                const aiVector3D& t = mesh->mTextureCoords[0][v];
                out.uvs.push_back({t.x, t.y});
            }
            if (!out.attributes.empty()) {
                const aiColor4D c =
                    mesh->HasVertexColors(0) ? mesh->mColors[0][v] : aiColor4D(1, 1, 1, 1);
                out.attributes[0].values.push_back({c.r, c.g, c.b});
                if (gltf && any_alpha) out.attributes[1].values.push_back(Color(c.a));
            }
        }
        MeshPart part{out.indices.size() / 3, 0, mesh->mMaterialIndex};
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;
            // Indices were checked before post-processing; Scene::add_mesh skips any triangle
            // whose index is still out of range.
            for (int k = 0; k < 3; ++k) out.indices.push_back(base + face.mIndices[k]);
            ++part.triangles;
        }
        if (part.material >= out.materials.size()) part.material = 0;
        if (part.triangles > 0) out.parts.push_back(part);
    }
    if (out.indices.empty()) throw std::runtime_error("the file holds no triangles");
    return out;
}

std::vector<Normal3> smooth_normals(const std::vector<Point3>& positions,
                                    const std::vector<uint32_t>& indices) {
    std::vector<Normal3> normals(positions.size(), Normal3{});
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
        if (a >= positions.size() || b >= positions.size() || c >= positions.size()) continue;
        Normal3 n = cross(positions[b] - positions[a], positions[c] - positions[a]);
        if (!is_finite(n)) continue;
        normals[a] += n;
        normals[b] += n;
        normals[c] += n;
    }
    for (Normal3& n : normals) {
        float len = length(n);
        n = len > 0 ? n / len : Normal3{};
    }
    return normals;
}

}  // namespace wavetrace
