#pragma once

#include <filesystem>
#include <string>

// Folders of the source tree, passed in by CMake.
inline std::filesystem::path scenes_dir() {
    return WAVETRACE_SCENES_DIR;
}
inline std::filesystem::path scene_path(const std::string& name) {
    return scenes_dir() / (name + ".json");
}
inline std::filesystem::path cli_path() {
    return WAVETRACE_CLI_PATH;
}
