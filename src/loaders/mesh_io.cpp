#include "loaders/mesh_io.h"

#include <algorithm>
#include <stdexcept>

#include "files/input_file.h"

namespace wavetrace {
namespace fs = std::filesystem;

MeshIO::MeshIO(const fs::path& mesh, const fs::path& asset_root)
    : confinement_{fs::absolute(mesh).lexically_normal().parent_path(), asset_root} {}

std::string MeshIO::problem(const fs::path& file) const {
    const fs::path p = fs::absolute(file).lexically_normal();
    if (std::string why = confinement_.problem(p); !why.empty()) return why;
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
