#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>

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

// Portable float map: "PF", size, a negative scale for little-endian, then rows bottom to
// top. Written here because Debian's OpenImageIO 2.4 reads PFM but has no PFM writer.
std::string write_pfm(const fs::path& path, const Image& image) {
    std::ofstream out(path, std::ios::binary);
    out << "PF\n" << image.width << " " << image.height << "\n-1.0\n";
    static_assert(std::endian::native == std::endian::little);
    for (int y = image.height - 1; y >= 0; --y)
        out.write(reinterpret_cast<const char*>(&image.at(0, y)),
                  static_cast<std::streamsize>(sizeof(Color)) * image.width);
    out.close();
    return out ? "" : std::string(std::strerror(errno));
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

    // Temporary name in the same folder, keeping the extension so that OpenImageIO picks the
    // same format; rename() then replaces the target atomically.
    fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    fs::path tmp = dir / ("." + path.stem().string() + ".tmp" + std::to_string(::getpid()) +
                          path.extension().string());
    std::string err;
    if (lower_extension(path) == ".pfm") {
        err = write_pfm(tmp, image);
    } else {
        auto out = OIIO::ImageOutput::create(tmp.string());
        if (!out) throw ImageError(path.string() + ": cannot write: " + OIIO::geterror());
        bool ok = out->open(tmp.string(), spec) &&
                  (ldr ? out->write_image(OIIO::TypeDesc::UINT8, bytes.data())
                       : out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data())) &&
                  out->close();
        if (!ok) err = out->geterror();
    }
    std::error_code ec;
    if (!err.empty()) {
        fs::remove(tmp, ec);
        throw ImageError(path.string() + ": cannot write: " + err);
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw ImageError(path.string() + ": cannot write: " + ec.message());
    }
}

ImageData read_image(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) {
        std::string err = OIIO::geterror();
        throw ImageError(path.string() +
                         ": cannot read image: " + (err.empty() ? "unknown error" : err));
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw ImageError(path.string() + ": empty image");
    const int channels = spec.nchannels;
    std::vector<float> data(static_cast<size_t>(spec.width) * spec.height * channels);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, data.data()))
        throw ImageError(path.string() + ": cannot read image: " + in->geterror());
    const bool decode = spec.format.basetype != OIIO::TypeDesc::FLOAT &&
                        spec.format.basetype != OIIO::TypeDesc::HALF &&
                        spec.format.basetype != OIIO::TypeDesc::DOUBLE;

    ImageData image;
    image.path = path.string();
    image.width = spec.width;
    image.height = spec.height;
    image.texels.resize(static_cast<size_t>(spec.width) * spec.height);
    for (size_t i = 0; i < image.texels.size(); ++i) {
        const float* px = &data[i * channels];
        Color c = channels >= 3 ? Color{px[0], px[1], px[2]} : Color{px[0]};
        if (decode) c = {srgb_decode(c.x), srgb_decode(c.y), srgb_decode(c.z)};
        if (!is_finite(c)) throw ImageError(path.string() + ": contains NaN or infinite texels");
        image.texels[i] = c;
    }
    return image;
}

}  // namespace wavetrace
