#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cctype>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "files/input_file.h"
#include "files/output_file.h"
#include "image/image_claims.h"
#include "wavetrace/image/image.h"

namespace wavetrace {
namespace fs = std::filesystem;
namespace {

std::string lower_extension(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// sRGB transfer functions (IEC 61966-2-1).
float srgb_encode(float linear) {
    return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}
float srgb_decode(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// srgb_decode of the 256 values an 8-bit channel reads as (k / 255), looked up instead of a
// pow per channel (a third of loading a scene of JPEG and PNG textures); any other value, and
// one that is not exactly k / 255, is decoded.
class SrgbBytes {
  public:
    SrgbBytes() {
        for (int k = 0; k < 256; ++k) decoded_[k] = srgb_decode(float(k) / 255.0f);
    }
    float decode(float encoded) const {
        const float scaled = encoded * 255.0f;
        if (scaled >= 0.0f && scaled <= 255.0f) {
            const int k = static_cast<int>(scaled + 0.5f);
            if (float(k) / 255.0f == encoded) return decoded_[k];
        }
        return srgb_decode(encoded);
    }

  private:
    float decoded_[256];
};

// Portable float map: "PF", size, a negative scale for little-endian, then rows bottom to
// top. Encoded here because Debian's OpenImageIO 2.4 reads PFM but has no PFM writer.
std::vector<unsigned char> encode_pfm(const Image& image) {
    std::string header =
        "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
    std::vector<unsigned char> out(header.begin(), header.end());
    static_assert(std::endian::native == std::endian::little);
    const size_t row = sizeof(Color) * static_cast<size_t>(image.width);
    out.reserve(out.size() + row * image.height);
    for (int y = image.height - 1; y >= 0; --y) {
        const auto* p = reinterpret_cast<const unsigned char*>(&image.at(0, y));
        out.insert(out.end(), p, p + row);
    }
    return out;
}

}  // namespace

bool is_ldr_path(const fs::path& path) {
    std::string ext = lower_extension(path);
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

void check_output_path(const fs::path& path) {
    std::string ext = lower_extension(path);
    if (!(is_ldr_path(path) || ext == ".exr" || ext == ".hdr" || ext == ".pfm"))
        throw ImageError(path.string() + ": unsupported output format '" + ext +
                         "' (use .png, .jpg, .exr, .hdr or .pfm)");
}

void check_output_writable(const fs::path& path) {
    check_output_path(path);
    std::error_code ec;
    if (fs::is_directory(path, ec))
        throw ImageError(path.string() + ": cannot write: is a directory");
    fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (!fs::is_directory(dir, ec))
        throw ImageError(path.string() + ": folder '" + dir.string() + "' does not exist");
    // Creating the write's own temporary file there is the one reliable test (permissions,
    // read-only mounts, ACLs, a name too long for the file system).
    const fs::path probe = temporary_path(path);
    int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0)
        throw ImageError(path.string() + ": cannot write in folder '" + dir.string() +
                         "': " + std::strerror(errno));
    ::close(fd);
    ::unlink(probe.c_str());
}

void write_image(const fs::path& path, const Image& image, const WriteOptions& options) {
    check_output_path(path);
    const bool ldr = is_ldr_path(path);
    const size_t n = static_cast<size_t>(image.width) * image.height;

    OIIO::ImageSpec spec(image.width, image.height, 3,
                         ldr ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT);
    for (const auto& [key, value] : options.metadata) spec.attribute(key, value);
    std::vector<uint8_t> bytes;
    if (ldr) {
        spec.attribute("oiio:ColorSpace", "sRGB");
        float scale = std::exp2(options.exposure);
        bytes.resize(n * 3);
        for (size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                float v = std::clamp(image.pixels[i][c] * scale, 0.0f, 1.0f);
                if (!(v == v)) v = 0.0f;  // NaN: clamp() keeps it; write black
                bytes[3 * i + c] = static_cast<uint8_t>(std::lround(255.0f * srgb_encode(v)));
            }
    } else {
        spec.attribute("oiio:ColorSpace", "Linear");
    }

    // Encode in memory, then write the bytes ourselves: every write is checked (a full disk
    // is an error, not a truncated image), and no codec can end the process mid-file (libjpeg
    // exits on a failed write).
    std::vector<unsigned char> encoded;
    if (lower_extension(path) == ".pfm") {
        encoded = encode_pfm(image);
    } else {
        auto out = OIIO::ImageOutput::create(path.string());
        if (!out) throw ImageError(path.string() + ": cannot write: " + OIIO::geterror());
        OIIO::Filesystem::IOVecOutput proxy(encoded);
        bool ok = out->set_ioproxy(&proxy) && out->open(path.string(), spec) &&
                  (ldr ? out->write_image(OIIO::TypeDesc::UINT8, bytes.data())
                       : out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data())) &&
                  out->close();
        if (!ok) throw ImageError(path.string() + ": cannot encode: " + out->geterror());
    }

    try {
        write_file_atomically(path, encoded);
    } catch (const std::runtime_error& e) {
        throw ImageError(path.string() + ": " + e.what());
    }
}

namespace {

// Colours as the file stores them beside an alpha channel: PNG's are not premultiplied (nor
// glTF's, nor Mitsuba's reading of them), and OpenImageIO would premultiply them on reading.
const OIIO::ImageSpec& unassociated_alpha() {
    static const OIIO::ImageSpec config = [] {
        OIIO::ImageSpec c;
        c.attribute("oiio:UnassociatedAlpha", 1);
        return c;
    }();
    return config;
}

// An opened image read whole as linear RGB (see read_image); `name` for messages.
ImageData read_opened(OIIO::ImageInput& in,
                      const std::string& name,
                      uint64_t file_bytes,
                      ImageChannels wanted) {
    const OIIO::ImageSpec& spec = in.spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw ImageError(name + ": empty image");
    // The header's claims, checked before anything is allocated for them.
    const uint64_t texels = uint64_t(spec.width) * uint64_t(spec.height);
    if (texels > kMaxImageTexels || spec.nchannels > 64)
        throw ImageError(name + ": image of " + std::to_string(spec.width) + " x " +
                         std::to_string(spec.height) + " x " + std::to_string(spec.nchannels) +
                         " channels exceeds the limit of " + std::to_string(kMaxImageTexels) +
                         " texels (and 64 channels)");
    if (texels > most_texels(in.format_name(), file_bytes))
        throw ImageError(name + ": the header claims " + std::to_string(spec.width) + " x " +
                         std::to_string(spec.height) + " pixels, more than a " +
                         in.format_name() + " file of " + std::to_string(file_bytes) +
                         " bytes can hold");
    const uint64_t row_bytes = uint64_t(spec.width) * uint64_t(spec.pixel_bytes(true));
    if (row_bytes > kMaxImageRowBytes)
        throw ImageError(name + ": rows of " + std::to_string(spec.width) + " pixels x " +
                         std::to_string(spec.nchannels) + " channels take " +
                         std::to_string(row_bytes) + " bytes, more than the limit of " +
                         std::to_string(kMaxImageRowBytes));
    if (spec.depth > 1) throw ImageError(name + ": volume images (depth > 1) are not read");
    // Only the channels used: RGB and alpha (the second of two, the fourth of four or more).
    const int channels = std::min(spec.nchannels, 4);
    const bool decode = wanted == ImageChannels::Linear &&
                        spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                        spec.format.basetype != OIIO::TypeDesc::HALF &&
                        spec.format.basetype != OIIO::TypeDesc::DOUBLE;

    ImageData image;
    image.path = name;
    image.width = spec.width;
    image.height = spec.height;
    // Read a band of rows at a time, so that a file whose pixels end early (a header claiming
    // more than its data holds) fails having touched memory only for the rows it had; the
    // reservation is address space until rows fill it.
    image.texels.reserve(static_cast<size_t>(texels));
    const size_t width = static_cast<size_t>(spec.width);
    const int band = static_cast<int>(
        std::clamp<size_t>((size_t(1) << 18) / (width * channels), 1, size_t(spec.height)));
    std::vector<float> data;
    static const SrgbBytes bytes;
    for (int y = 0; y < spec.height; y += band) {
        const int rows = std::min(band, spec.height - y);
        data.resize(width * rows * channels);
        if (!in.read_scanlines(0, 0, spec.y + y, spec.y + y + rows, spec.z, 0, channels,
                               OIIO::TypeDesc::FLOAT, data.data())) {
            const std::string err = in.geterror();
            throw ImageError(name + ": cannot read image: " +
                             (err.empty() ? "the pixels end early or are malformed" : err));
        }
        for (size_t i = 0; i < width * rows; ++i) {
            const float* px = &data[i * channels];
            Color c = channels >= 3 ? Color{px[0], px[1], px[2]} : Color{px[0]};
            if (wanted == ImageChannels::Alpha)
                c = Color(channels == 2 || channels >= 4 ? px[channels == 2 ? 1 : 3] : 1.0f);
            if (decode) c = {bytes.decode(c.x), bytes.decode(c.y), bytes.decode(c.z)};
            if (!is_finite(c)) throw ImageError(name + ": contains NaN or infinite texels");
            image.texels.push_back(c);
        }
    }
    return image;
}

}  // namespace

ImageData read_image(const fs::path& path, ImageChannels channels) {
    try {
        check_input_file(path, kMaxImageFileBytes, "images");
    } catch (const std::runtime_error& e) {
        throw ImageError(path.string() + ": cannot read image: " + e.what());
    }
    std::error_code ec;
    const uintmax_t bytes = fs::file_size(path, ec);
    {
        std::ifstream file(path, std::ios::binary);
        check_image_claims(
            ec ? 0 : uint64_t(bytes),
            [&](uint64_t at, size_t n, unsigned char* out) {
                file.clear();
                file.seekg(static_cast<std::streamoff>(at));
                return bool(file.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n)));
            },
            path.string());
    }
    auto in = OIIO::ImageInput::open(path.string(), &unassociated_alpha());
    if (!in) {
        std::string err = OIIO::geterror();
        throw ImageError(path.string() +
                         ": cannot read image: " + (err.empty() ? "unknown error" : err));
    }
    return read_opened(*in, path.string(), ec ? 0 : uint64_t(bytes), channels);
}

ImageData read_image_bytes(std::span<const unsigned char> bytes,
                           const std::string& format,
                           const std::string& name,
                           ImageChannels channels) {
    if (format != "png" && format != "jpg" && format != "jpeg")
        throw ImageError(name + ": cannot read image: format \"" + format +
                         "\" (embedded images are read as png or jpeg)");
    check_image_claims(
        bytes.size(),
        [&](uint64_t at, size_t n, unsigned char* out) {
            if (at + n > bytes.size()) return false;
            std::memcpy(out, bytes.data() + at, n);
            return true;
        },
        name);
    // The reader is chosen by the name's extension and reads from memory through the proxy.
    OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
    OIIO::ImageSpec config = unassociated_alpha();
    void* proxy_pointer = &proxy;  // with a config, the proxy travels in it
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy_pointer);
    auto in = OIIO::ImageInput::open("embedded." + format, &config, &proxy);
    if (!in) {
        std::string err = OIIO::geterror();
        throw ImageError(name + ": cannot read image: " + (err.empty() ? "unknown error" : err));
    }
    return read_opened(*in, name, bytes.size(), channels);
}

}  // namespace wavetrace
