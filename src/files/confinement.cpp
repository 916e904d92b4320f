#include "files/confinement.h"

#include <algorithm>

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

std::string Confinement::problem(const fs::path& path) const {
    if (!folder.empty() && !inside(normalized(path), normalized(folder)))
        return "outside the folder " + normalized(folder).string() +
               " (a file's own references may not leave it)";
    if (!root.empty()) {
        std::error_code ec;
        const fs::path real = fs::weakly_canonical(fs::absolute(path), ec);
        const fs::path real_root = fs::weakly_canonical(fs::absolute(root), ec);
        if (ec || !inside(real, real_root))
            return "outside the asset root " + real_root.string();
    }
    return "";
}

}  // namespace wavetrace
