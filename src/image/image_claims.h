// What an image file's header claims, checked against what the file can hold before any
// reader allocates for it: image libraries size their buffers from such claims (a PNG chunk's
// length, an OpenEXR attribute's size, the pixel count) and only then find the bytes missing,
// so a file of a few hundred bytes could make them allocate and clear gigabytes.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace wavetrace {

// The most texels a file of `bytes` bytes can hold in `format` (OpenImageIO's format name).
uint64_t most_texels(const std::string& format, uint64_t bytes);

// Reads n bytes at an offset into `out`; false past the end of the file.
using ReadAt = std::function<bool(uint64_t offset, size_t n, unsigned char* out)>;

// Walks the container of a PNG (its chunks) or an OpenEXR file (its headers' attributes) of
// `size` bytes and throws ImageError, prefixed with `name`, where a length, a size or the
// data window claims more than the file holds. Any other file, and a structure too damaged to
// walk, is left to its reader.
void check_image_claims(uint64_t size, const ReadAt& read_at, const std::string& name);

}  // namespace wavetrace
