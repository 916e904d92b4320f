#include "mesh_file.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <stdexcept>

namespace wavetrace {

MeshFile read_mesh_file(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw std::runtime_error("no such file");
    if (std::filesystem::is_directory(path, ec)) throw std::runtime_error("is a directory");
    Assimp::Importer importer;
    std::string ext = path.extension().string();
    if (ext.empty() || !importer.IsExtensionSupported(ext))
        throw std::runtime_error("unsupported mesh format '" + ext +
                                 "' (Assimp reads e.g. .obj, .ply, .gltf, .glb, .stl)");
    // Keep only triangles. Assimp's OBJ reader un-indexes faces; joining identical vertices
    // restores the shared indexing (and the memory) of the file.
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                                aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* scene = importer.ReadFile(
        path.string(), aiProcess_Triangulate | aiProcess_PreTransformVertices |
                           aiProcess_SortByPType | aiProcess_JoinIdenticalVertices);
    if (!scene || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode)
        throw std::runtime_error(importer.GetErrorString());

    MeshFile out;
    bool all_normals = true, all_uvs = true;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[m];
        if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
        all_normals = all_normals && mesh->HasNormals();
        all_uvs = all_uvs && mesh->HasTextureCoords(0);
    }
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
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            const aiFace& face = mesh->mFaces[f];
            if (face.mNumIndices != 3) continue;
            for (int k = 0; k < 3; ++k) out.indices.push_back(base + face.mIndices[k]);
        }
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
