// Checks on a file before it is opened for reading: it must be a regular file (a FIFO, a
// device such as /dev/zero or a directory would hang or exhaust memory) of at most a given
// size. Scene files, meshes and images all pass through here.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace wavetrace {

// Throws std::runtime_error with a short reason ("no such file", "not a regular file (a
// FIFO)", "is 3.2 GiB; the limit for meshes is 2 GiB") that callers prefix with the file and
// the place that named it.
void check_input_file(const std::filesystem::path& path, uintmax_t max_bytes, const char* kind);

// The whole file as bytes, for a file that passed check_input_file. Throws std::runtime_error
// ("out of memory reading its 35.0 MiB", or the system's reason) that callers prefix as above:
// a stream read into a growing buffer would instead stop quietly where memory ran out.
std::string read_input_file(const std::filesystem::path& path);

// Limits, documented in docs/scene-format.md.
inline constexpr uintmax_t kMaxSceneFileBytes = uintmax_t(64) << 20;  // 64 MiB of JSON
inline constexpr uintmax_t kMaxMeshFileBytes = uintmax_t(2) << 30;    // 2 GiB
inline constexpr uintmax_t kMaxImageFileBytes = uintmax_t(1) << 30;   // 1 GiB

}  // namespace wavetrace
