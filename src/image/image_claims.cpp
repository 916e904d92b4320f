#include "image/image_claims.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <vector>

#include "wavetrace/image/image.h"

namespace wavetrace {
namespace {

uint32_t big_endian_32(const unsigned char* p) {
    return (uint32_t(p[0]) << 24) | (uint32_t(p[1]) << 16) | (uint32_t(p[2]) << 8) | p[3];
}
int32_t little_endian_32(const unsigned char* p) {
    return static_cast<int32_t>(uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) |
                                (uint32_t(p[3]) << 24));
}

// A name as a message can show it: what is not printable becomes '?'.
std::string printable(std::string s) {
    for (char& c : s)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    return s;
}

// PNG (ISO/IEC 15948, section 5.3): after the signature, chunks of a 4-byte big-endian length,
// a 4-byte type, the data and a CRC, up to IEND. libpng allocates a chunk's claimed length
// before reading it: a 600-byte file whose tEXt chunk claimed 2 GB took 5 s and 2 GB to fail.
void check_png(uint64_t size, const ReadAt& read_at, const std::string& name) {
    unsigned char head[8];
    for (uint64_t at = 8; at + 8 <= size;) {
        if (!read_at(at, 8, head)) return;
        const uint64_t length = big_endian_32(head);
        const std::string type = printable(std::string(reinterpret_cast<char*>(head + 4), 4));
        const uint64_t after_header = size - at - 8;  // its data and CRC must fit here
        if (length + 4 > after_header)
            throw ImageError(name + ": cannot read image: PNG chunk '" + type + "' at byte " +
                             std::to_string(at) + " claims " + std::to_string(length) +
                             " bytes; the file has " + std::to_string(after_header) +
                             " after its header");
        if (type == "IEND") return;
        at += 12 + length;
    }
}

// OpenEXR ("OpenEXR File Layout"): after the magic number and the version field, a header of
// attributes, each a NUL-terminated name, a NUL-terminated type name, a 4-byte little-endian
// size and that many bytes of value, closed by an empty name; a multi-part file has one header
// per part and an empty header after the last. OpenEXR sizes a string attribute's buffer by
// its claimed size before reading it, and its tables by the data window.
void check_exr(uint64_t size, const ReadAt& read_at, const std::string& name) {
    unsigned char version[4];
    if (!read_at(4, 4, version)) return;
    const bool multipart = (version[1] & 0x10) != 0;  // flag bit 12
    uint64_t at = 8;
    // The NUL-terminated string at `at` (names are at most 255 bytes); false if none ends there.
    auto read_string = [&](std::string& out) {
        unsigned char buffer[256];
        const size_t n = static_cast<size_t>(std::min<uint64_t>(sizeof buffer, size - at));
        if (at >= size || !read_at(at, n, buffer)) return false;
        const void* end = std::memchr(buffer, 0, n);
        if (!end) return false;
        out.assign(reinterpret_cast<const char*>(buffer), static_cast<const char*>(end));
        at += out.size() + 1;
        return true;
    };
    // A channel list's bytes a pixel: each channel a NUL-terminated name, a 4-byte pixel type
    // (0 uint, 1 half, 2 float) and 12 bytes of flags and sampling; an empty name ends it.
    auto chlist_bytes = [&](uint64_t from, uint64_t length) {
        std::vector<unsigned char> list(static_cast<size_t>(std::min<uint64_t>(length, 1 << 16)));
        if (!read_at(from, list.size(), list.data())) return uint64_t(0);
        uint64_t bytes = 0;
        for (size_t i = 0; i < list.size() && list[i] != 0;) {
            const void* end = std::memchr(&list[i], 0, list.size() - i);
            if (!end) break;
            i = size_t(static_cast<const unsigned char*>(end) - list.data()) + 1;
            if (i + 16 > list.size()) break;
            bytes += little_endian_32(&list[i]) == 1 ? 2 : 4;
            i += 16;
        }
        return bytes;
    };
    for (;;) {  // each part's header
        std::string attribute, type;
        int64_t width = 0;         // of the data window
        uint64_t pixel_bytes = 0;  // the channels' sizes (2 for half, 4 for float and uint)
        for (;;) {                 // each attribute
            if (!read_string(attribute)) return;
            if (attribute.empty()) {
                // OpenEXR sizes its line buffers by the row, for up to 256 rows (DWAB), and
                // OpenImageIO converts through 256 rows, whatever the image's height.
                const uint64_t row_bytes = uint64_t(std::max<int64_t>(width, 0)) * pixel_bytes;
                if (row_bytes > kMaxImageRowBytes)
                    throw ImageError(name + ": the header claims rows of " + std::to_string(width) +
                                     " pixels x " + std::to_string(pixel_bytes) +
                                     " bytes, more than the limit of " +
                                     std::to_string(kMaxImageRowBytes) + " bytes a row");
                break;
            }
            const uint64_t attribute_at = at - attribute.size() - 1;
            unsigned char length[4];
            if (!read_string(type) || !read_at(at, 4, length)) return;
            at += 4;
            const int32_t claimed = little_endian_32(length);
            if (claimed < 0 || uint64_t(claimed) > size - at)
                throw ImageError(name + ": cannot read image: OpenEXR attribute '" +
                                 printable(attribute) + "' at byte " +
                                 std::to_string(attribute_at) + " claims " +
                                 std::to_string(claimed) + " bytes; the file has " +
                                 std::to_string(size - at) + " after it");
            if (attribute == "channels" && type == "chlist")
                pixel_bytes = chlist_bytes(at, uint64_t(claimed));
            unsigned char box[16];
            if (attribute == "dataWindow" && type == "box2i" && claimed == 16 &&
                read_at(at, 16, box)) {
                width = int64_t(little_endian_32(box + 8)) - little_endian_32(box) + 1;
                const int64_t height =
                    int64_t(little_endian_32(box + 12)) - little_endian_32(box + 4) + 1;
                const std::string claim = name + ": the header claims " + std::to_string(width) +
                                          " x " + std::to_string(height) + " pixels, ";
                const uint64_t texels = uint64_t(width) * uint64_t(height);
                if (width > 0 && height > 0 && texels > kMaxImageTexels)
                    throw ImageError(claim + "more than the limit of " +
                                     std::to_string(kMaxImageTexels) + " texels");
                if (width > 0 && height > 0 && texels > most_texels("openexr", size))
                    throw ImageError(claim + "more than an openexr file of " +
                                     std::to_string(size) + " bytes can hold");
            }
            at += uint64_t(claimed);
        }
        unsigned char next;
        if (!multipart || !read_at(at, 1, &next) || next == 0) return;
    }
}

}  // namespace

// PNM stores every pixel (at least a bit each); every other format compresses at most ~1000:1
// (deflate's limit) of at least a bit per texel, for which 2^14 texels a byte leave room, plus
// a header's worth.
uint64_t most_texels(const std::string& format, uint64_t bytes) {
    if (format == "pnm") return 8 * bytes;
    return (uint64_t(1) << 14) * bytes + (uint64_t(1) << 16);
}

void check_image_claims(uint64_t size, const ReadAt& read_at, const std::string& name) {
    static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char kExr[4] = {0x76, 0x2f, 0x31, 0x01};
    unsigned char magic[8];
    if (size < 8 || !read_at(0, 8, magic)) return;
    if (std::memcmp(magic, kPng, 8) == 0) check_png(size, read_at, name);
    if (std::memcmp(magic, kExr, 4) == 0) check_exr(size, read_at, name);
}

}  // namespace wavetrace
