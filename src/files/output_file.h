// Writing a file so that it appears whole or not at all: what the image writer and the film
// files use.
#pragma once

#include <filesystem>
#include <vector>

namespace wavetrace {

// Writes `bytes` to a temporary file in the same folder with every write checked, flushes it
// to disk and renames it over `path`: a failed write (a full disk, a signal) keeps the
// previous file and leaves no temporary file. Throws std::runtime_error("cannot write: why").
void write_file_atomically(const std::filesystem::path& path,
                           const std::vector<unsigned char>& bytes);

// The temporary file write_file_atomically() writes before renaming it to `path`: a hidden
// name beside it, ".NAME.tmpPID". Creating it is the test that `path` can be written (a name
// too long for the file system fails here, not after a render).
std::filesystem::path temporary_path(const std::filesystem::path& path);

}  // namespace wavetrace
