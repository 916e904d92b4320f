#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "wavetrace/math/vec3.h"
#include "wavetrace/scene/texture.h"

namespace wavetrace {

// A linear RGB float image, row 0 at the top.
struct Image {
    int width = 0;
    int height = 0;
    std::vector<Color> pixels;

    Image() = default;
    Image(int w, int h) : width(w), height(h), pixels(static_cast<size_t>(w) * h) {}
    Color& at(int x, int y) { return pixels[static_cast<size_t>(y) * width + x]; }
    const Color& at(int x, int y) const { return pixels[static_cast<size_t>(y) * width + x]; }
};

class ImageError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct WriteOptions {
    float exposure = 0.0f;  // LDR outputs are scaled by 2^exposure before encoding
    // Extra string attributes stored in the file's metadata (EXR header, PNG text).
    std::vector<std::pair<std::string, std::string>> metadata;
};

// Whether the extension of `path` names an 8-bit display format (PNG, JPEG) as opposed to a
// linear float one (EXR, HDR, PFM).
bool is_ldr_path(const std::filesystem::path& path);
// Throws ImageError unless the extension is one write_image() handles.
void check_output_path(const std::filesystem::path& path);
// check_output_path(), and that a file can be created there: not a directory, in an existing
// folder we may write in. For checking before a long render.
void check_output_writable(const std::filesystem::path& path);

// Writes by extension: .png/.jpg/.jpeg as 8-bit sRGB (clamped), .exr (32-bit float),
// .hdr, .pfm as linear float. The file appears atomically: it is encoded in memory, written to
// a temporary file in the same folder with every write checked, flushed and renamed, so a
// failed write (a full disk, a signal) keeps the previous file and leaves no temporary file.
void write_image(const std::filesystem::path& path,
                 const Image& image,
                 const WriteOptions& options = {});

// The most texels read_image() accepts (the header is checked before anything is allocated):
// 2^26, e.g. 8192 x 8192, which take 768 MiB as linear RGB floats.
inline constexpr uint64_t kMaxImageTexels = uint64_t(1) << 26;

// The longest row read_image() accepts, in the file's own channels and types: 1 MiB, e.g.
// 65536 RGBA texels of 32-bit floats. OpenImageIO converts through a buffer of 256 rows
// whatever the image's height, so a one-row header with millions of columns would otherwise
// allocate gigabytes.
inline constexpr uint64_t kMaxImageRowBytes = uint64_t(1) << 20;

// What read_image takes from a file's channels.
enum class ImageChannels {
    Linear,  // linear RGB: 8- and 16-bit integer files are taken as sRGB-encoded and decoded
    Raw,     // RGB values as stored, in [0, 1] for integer files (data such as normal maps, as
             // Mitsuba's `raw` bitmaps)
    Alpha,   // the alpha channel (the last of 2 or 4) as stored, as grey; 1 where there is none
};

// Reads any image OpenImageIO can, as the channels ask; float files (EXR, HDR, PFM) are linear
// as they are. Grey images are expanded.
ImageData read_image(const std::filesystem::path& path,
                     ImageChannels channels = ImageChannels::Linear);
// The same for an encoded image held in memory (`format`: "png", "jpg" or "jpeg"), e.g. one
// embedded in a glTF file; `name` stands for it in messages.
ImageData read_image_bytes(std::span<const unsigned char> bytes,
                           const std::string& format,
                           const std::string& name,
                           ImageChannels channels = ImageChannels::Linear);

}  // namespace wavetrace
