// Where a scene may read files from. A file's own references (a mesh's MTL, buffers and
// textures) stay inside its folder: "../" may not climb out of it, nor an absolute name lead
// elsewhere (compared lexically, so that a folder of links into a texture library still
// works). With an asset root (a render farm's), every file must lie inside it once symbolic
// links are resolved.
#pragma once

#include <filesystem>
#include <string>

namespace wavetrace {

struct Confinement {
    std::filesystem::path folder;  // empty: no folder to stay in
    std::filesystem::path root;    // empty: no asset root

    // Why `path` may not be read ("outside the asset root /farm/assets"), or "" if it may.
    std::string problem(const std::filesystem::path& path) const;
};

}  // namespace wavetrace
