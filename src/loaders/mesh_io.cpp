#include "loaders/mesh_io.h"

#include <algorithm>
#include <stdexcept>

#include "files/input_file.h"

namespace wavetrace {
namespace fs = std::filesystem;

namespace {

// Whether `path` is `folder` or lies below it (both absolute and normalized).
bool inside(const fs::path& path, const fs::path& folder) {
    auto [f, p] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
    // A trailing empty element (a folder written with a final separator) matches anything.
    return f == folder.end() || (std::next(f) == folder.end() && f->empty());
}

fs::path normalized(const fs::path& p) {
    return fs::absolute(p).lexically_normal();
}

}  // namespace

MeshIO::MeshIO(const fs::path& mesh) : folder_(normalized(mesh).parent_path()) {}

std::string MeshIO::problem(const fs::path& file) const {
    const fs::path p = normalized(file);
    if (!inside(p, folder_))
        return "outside the mesh's folder " + folder_.string() +
               " (a mesh's own references may not leave it)";
    try {
        check_input_file(p, kMaxMeshFileBytes, "meshes");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

void MeshIO::note(const fs::path& file, const std::string& why) const {
    auto& list = why == "no such file" ? missing_ : refused_;
    const std::string entry = file.string() + ": " + why;
    if (std::find(list.begin(), list.end(), entry) == list.end()) list.push_back(entry);
}

bool MeshIO::Exists(const char* file) const {
    const std::string why = problem(file);
    if (why.empty()) return true;
    note(file, why);
    return false;
}

Assimp::IOStream* MeshIO::Open(const char* file, const char* mode) {
    const std::string m = mode ? mode : "rb";
    if (m.find_first_of("wa+") != std::string::npos) {
        note(file, "Assimp asked to write it");
        return nullptr;
    }
    const std::string why = problem(file);
    if (!why.empty()) {
        note(file, why);
        return nullptr;
    }
    return DefaultIOSystem::Open(file, mode);
}

}  // namespace wavetrace
