// The source tree's layering (docs/architecture.md, "Layout"): folders of src/ and of
// include/wavetrace/ are layers, and a file includes only its own layer and those below it.
// This reads the includes of every file, as a reader drawing the structure would.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Lowest first. The public headers of include/wavetrace/<layer>/ belong to that layer.
const std::vector<std::string> kLayers = {
    "util",         // invariant checks
    "math",         // small float math, SIMD lane types
    "files",        // reading an input file whole, writing an output atomically
    "sampling",     // the counter-based sampler, warps, tabulated distributions
    "microfacets",  // microfacet distributions: densities, Smith masking, visible normals
    "bsdfs",        // how surfaces and media scatter: BSDFs, Fresnel, microfacet distributions
    "scene",        // the scene model and its builders
    "media",        // media: free flights, transmittance, grid tracking, the medium stack
    "image",        // images: OpenImageIO in and out, comparisons
    "film",         // per-pixel sums and film files
    "formats",      // file formats read strictly: JSON, glTF's JSON, checks before Assimp
    "mitsuba",      // Mitsuba XML scene files into our JSON document
    "pbrt",         // pbrt-v4 scene files into our JSON document
    "loaders",      // scene files and mesh files into a Scene
    "accel",        // the BVH: build, wide layout, traversal, primitive tests
    "lights",       // which light a vertex samples: lights' bounds, importance, selection
    "shading",      // what both engines share: surfaces, lights, MIS, media, path vertices
    "queues",       // the wavefront's structure-of-arrays queues
    "blocks",       // a chunk's lane blocks (SoA rows) and the SIMD kernels over them
    "kernels",      // the wavefront's kernels
    "engines",      // both engines, the AOV renderer, render()
    "embree",       // Embree as the reference intersector (tests and benchmarks only)
};

int rank_of(const std::string& layer) {
    auto it = std::find(kLayers.begin(), kLayers.end(), layer);
    return it == kLayers.end() ? -1 : static_cast<int>(it - kLayers.begin());
}

fs::path source_dir() {
    return fs::path(WAVETRACE_SCENES_DIR).parent_path();
}

struct Include {
    std::string target;  // as written between the quotes
    int line;
};

std::vector<Include> includes_of(const fs::path& file) {
    static const std::regex re(R"(^\s*#\s*include\s*"([^"]+)\")");
    std::vector<Include> out;
    std::ifstream in(file);
    std::string text;
    for (int line = 1; std::getline(in, text); ++line) {
        std::smatch m;
        if (std::regex_search(text, m, re)) out.push_back({m[1].str(), line});
    }
    return out;
}

// The layer an include names: "wavetrace/<layer>/..." (public) or "<layer>/..." (src/); empty
// for anything else (a header beside the file, a top-level public header).
std::string layer_of_include(const std::string& target) {
    std::string t = target;
    if (t.rfind("wavetrace/", 0) == 0) t = t.substr(10);
    const size_t slash = t.find('/');
    return slash == std::string::npos ? "" : t.substr(0, slash);
}

bool is_source(const fs::path& p) {
    const std::string e = p.extension().string();
    return e == ".h" || e == ".cpp";
}

// Files under `root` grouped by their first folder.
std::map<std::string, std::vector<fs::path>> files_by_folder(const fs::path& root) {
    std::map<std::string, std::vector<fs::path>> out;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file() || !is_source(entry.path())) continue;
        const fs::path rel = fs::relative(entry.path(), root);
        if (rel.begin() == rel.end() || std::next(rel.begin()) == rel.end()) continue;
        out[rel.begin()->string()].push_back(entry.path());
    }
    return out;
}

}  // namespace

TEST(Layers, EveryFolderIsALayer) {
    for (const fs::path& root : {source_dir() / "src", source_dir() / "include" / "wavetrace"})
        for (const auto& [folder, files] : files_by_folder(root))
            EXPECT_GE(rank_of(folder), 0)
                << root / folder << " is no layer: place it in kLayers and docs/architecture.md";
}

TEST(Layers, NoIncludeRunsUpward) {
    for (const fs::path& root : {source_dir() / "src", source_dir() / "include" / "wavetrace"})
        for (const auto& [folder, files] : files_by_folder(root)) {
            const int rank = rank_of(folder);
            for (const fs::path& file : files)
                for (const Include& inc : includes_of(file)) {
                    const std::string to = layer_of_include(inc.target);
                    if (to.empty()) continue;
                    EXPECT_LE(rank_of(to), rank)
                        << file.string() << ":" << inc.line << " (" << folder << ") includes "
                        << inc.target << " (" << to << "), a layer above it";
                }
        }
}

// A library user gets the public headers only: none may reach into src/.
TEST(Layers, PublicHeadersIncludeOnlyPublicHeaders) {
    const fs::path root = source_dir() / "include";
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file()) continue;
        for (const Include& inc : includes_of(entry.path()))
            EXPECT_EQ(inc.target.rfind("wavetrace/", 0), 0u)
                << entry.path().string() << ":" << inc.line << " includes " << inc.target
                << ", which is not a public header";
    }
}

// Small folders stay readable: a folder past this many lines holds more than one concept.
TEST(Layers, NoFolderOfSrcIsOverTwoAndAHalfThousandLines) {
    for (const auto& [folder, files] : files_by_folder(source_dir() / "src")) {
        size_t lines = 0;
        for (const fs::path& file : files) {
            std::ifstream in(file);
            lines += static_cast<size_t>(std::count(std::istreambuf_iterator<char>(in),
                                                    std::istreambuf_iterator<char>(), '\n'));
        }
        EXPECT_LE(lines, 2500u) << "src/" << folder << " has " << lines << " lines";
    }
}
