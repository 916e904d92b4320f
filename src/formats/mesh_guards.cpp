#include "formats/mesh_guards.h"

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace wavetrace {

// Assimp 5.2's OFF reader allocates what the header's vertex and face counts ask for before
// reading any of them, so a short file claiming 10^10 vertices allocates tens of GiB (found
// by tests/fuzz/fuzz_mesh). Every vertex and face takes at least two bytes of text, which
// bounds the counts a file of its size can hold.
void check_off(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string word;
    std::vector<std::pair<double, std::string>> counts;  // value, as written
    bool magic = false;
    while (counts.size() < 2 && in >> word) {
        if (word[0] == '#') {
            std::getline(in, word);
            continue;
        }
        if (!magic) {
            magic = true;
            if (word.size() >= 3 && word.compare(word.size() - 3, 3, "OFF") == 0) continue;
        }
        char* end = nullptr;
        double v = std::strtod(word.c_str(), &end);
        if (*end != '\0' || !(v >= 0))
            throw std::runtime_error("OFF header: bad count '" + word + "'");
        counts.push_back({v, word});
    }
    std::error_code ec;
    const double size = double(std::filesystem::file_size(path, ec));
    for (const auto& [count, text] : counts)
        if (count > size / 2)
            throw std::runtime_error("OFF header announces " + text +
                                     " elements, more than a file of " +
                                     std::to_string(uint64_t(size)) + " bytes can hold");
}

// Assimp 5.2's OBJ reader makes a mesh and a material for every name `usemtl` gives, and its
// post-processing then takes time that grows faster than their count (100,000 names in 5 MB:
// over 40 s and 3.7 GB); its triangulation clips ears in time quadratic in a polygon's
// vertices (five polygons of 32,767 vertices in 1.7 MB: over a minute). Both are bounded
// here: at most kMaxObjMaterials names, and at most kMaxObjPolygonWork for the sum of n^2
// over the polygons of n >= 5 vertices (quads and triangles cost nothing to split).
// Assimp 5.2's MTL reader applies a statement before the first `newmtl` to a material that
// does not exist: a texture there (`map_Kd t.png`) writes through a null pointer (a segfault
// on a two-line file, found by fuzz_mesh). Every statement must follow a `newmtl`.
void check_mtl(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    size_t line_number = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        std::istringstream words(line);
        std::string key;
        if (!(words >> key) || key[0] == '#') continue;
        if (key == "newmtl") return;
        throw std::runtime_error("material library " + path.filename().string() + " line " +
                                 std::to_string(line_number) + ": '" + key +
                                 "' before the first newmtl");
    }
}

void check_obj(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    // The material libraries Assimp will read: those `mtllib` names, else the OBJ's own name
    // with .mtl.
    const std::filesystem::path folder = path.parent_path();
    std::vector<std::filesystem::path> libraries = {path.parent_path() /
                                                    (path.stem().string() + ".mtl")};
    std::set<std::string> names;
    uint64_t work = 0;
    size_t line_number = 0;
    std::string line, logical;
    while (std::getline(in, line)) {
        ++line_number;
        // A backslash at the end of a line continues it, for Assimp as for the format.
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (!line.empty() && line.back() == '\\') {
            logical += line.substr(0, line.size() - 1) + " ";
            continue;
        }
        logical += line;
        std::istringstream words(logical);
        logical.clear();
        std::string key;
        if (!(words >> key)) continue;
        if (key == "mtllib") {
            std::string name;
            std::getline(words >> std::ws, name);
            libraries.push_back(folder / name);
        } else if (key == "usemtl") {
            std::string name;
            std::getline(words >> std::ws, name);
            names.insert(name);
            if (names.size() > kMaxObjMaterials)
                throw std::runtime_error("line " + std::to_string(line_number) +
                                         ": more than " + std::to_string(kMaxObjMaterials) +
                                         " material names (usemtl)");
        } else if (key == "f") {
            uint64_t n = 0;
            for (std::string v; words >> v;) ++n;
            if (n >= 5) work += n * n;
            if (work > kMaxObjPolygonWork)
                throw std::runtime_error(
                    "line " + std::to_string(line_number) + ": polygons too large to triangulate " +
                    "(the sum of their vertex counts squared passes " +
                    std::to_string(kMaxObjPolygonWork) + "); split them into smaller ones");
        }
    }
    for (const std::filesystem::path& library : libraries) {
        std::error_code ec;
        if (std::filesystem::is_regular_file(library, ec)) check_mtl(library);
    }
}

}  // namespace wavetrace
