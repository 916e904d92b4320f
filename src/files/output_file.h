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

}  // namespace wavetrace
