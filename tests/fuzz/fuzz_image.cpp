// libFuzzer target: an image file (a texture, an environment map, a mask) through read_image:
// our header checks (claimed size against the limit and against what the file's bytes can
// hold) and then OpenImageIO's reader. The first byte picks the format (the extension: PNG,
// JPEG, Radiance HDR, PPM, PFM, OpenEXR, TGA) and the channels read (linear, raw, alpha); the
// rest is the file. PNG and JPEG also go through read_image_bytes, as a glTF file's embedded
// images do.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include "wavetrace/image/image.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    static const char* kExtensions[] = {"png", "jpg", "hdr", "ppm", "pfm", "exr", "tga"};
    static const wavetrace::ImageChannels kChannels[] = {wavetrace::ImageChannels::Linear,
                                                         wavetrace::ImageChannels::Raw,
                                                         wavetrace::ImageChannels::Alpha};
    static const fs::path dir = [] {
        fs::path d =
            fs::temp_directory_path() / ("wavetrace-fuzz-image-" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    const std::string extension = kExtensions[data[0] % 7];
    const wavetrace::ImageChannels channels = kChannels[(data[0] / 7) % 3];
    const fs::path file = dir / ("i." + extension);
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    }
    try {
        (void)wavetrace::read_image(file, channels);
    } catch (const wavetrace::ImageError&) {
    }
    if (extension == "png" || extension == "jpg") {
        try {
            (void)wavetrace::read_image_bytes(std::span<const unsigned char>(data + 1, size - 1),
                                              extension, "embedded", channels);
        } catch (const wavetrace::ImageError&) {
        }
    }
    fs::remove(file);
    return 0;
}
