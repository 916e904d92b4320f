#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "temp_dir.h"
#include "wavetrace/image/image.h"

using namespace wavetrace;

namespace {
Image gradient(int w, int h) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) img.at(x, y) = {x / float(w), y / float(h), 0.25f * (x + y)};
    return img;
}
}  // namespace

TEST(ImageIo, ExrAndPfmKeepLinearFloats) {
    TempDir dir;
    Image img = gradient(7, 5);
    img.at(3, 2) = {123.5f, -1.0f, 1e-3f};  // HDR and negative values survive float formats
    for (const char* name : {"a.exr", "a.pfm"}) {
        write_image(dir.path() / name, img);
        ImageData back = read_image(dir.path() / name);
        ASSERT_EQ(back.width, 7);
        ASSERT_EQ(back.height, 5);
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 7; ++x) EXPECT_EQ(back.texel(x, y), img.at(x, y)) << name;
    }
}

TEST(ImageIo, PngIsSrgbEncodedAndClamped) {
    TempDir dir;
    Image img(4, 1);
    img.at(0, 0) = Color(0.0f);
    img.at(1, 0) = Color(0.5f);
    img.at(2, 0) = Color(1.0f);
    img.at(3, 0) = Color(7.0f);  // clamped to 1
    write_image(dir.path() / "a.png", img);
    ImageData back = read_image(dir.path() / "a.png");  // decodes sRGB back to linear
    EXPECT_EQ(back.texel(0, 0).x, 0.0f);
    EXPECT_NEAR(back.texel(1, 0).x, 0.5f, 0.005f);  // 8-bit quantization of sRGB(0.5) = 188
    EXPECT_EQ(back.texel(2, 0).x, 1.0f);
    EXPECT_EQ(back.texel(3, 0).x, 1.0f);
    // Exposure +1 stop doubles before encoding.
    WriteOptions opt;
    opt.exposure = 1.0f;
    write_image(dir.path() / "b.png", img, opt);
    EXPECT_NEAR(read_image(dir.path() / "b.png").texel(1, 0).x, 1.0f, 1e-6f);
}

TEST(ImageIo, WritesAreAtomicAndLeaveNoTemporaryFiles) {
    TempDir dir;
    write_image(dir.path() / "ok.hdr", gradient(8, 8));
    write_image(dir.path() / "ok.jpg", gradient(8, 8));
    EXPECT_THROW(write_image(dir.path() / "missing" / "x.png", gradient(8, 8)), ImageError);
    EXPECT_THROW(write_image(dir.path() / "x.bmpx", gradient(8, 8)), ImageError);
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir.path()))
        names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"ok.hdr", "ok.jpg"}));
}

TEST(ImageIo, ReadingGarbageFailsWithThePath) {
    TempDir dir;
    auto p = dir.write("bad.exr", "not an exr");
    try {
        read_image(p);
        FAIL();
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos);
    }
    EXPECT_THROW(read_image(dir.path() / "none.png"), ImageError);
}

// A PNG chunk claiming more bytes than the file has is refused before libpng allocates it (a
// 600-byte file whose tEXt chunk claimed 1.9 GB took 5 s and 2 GB to fail), from a file and from
// memory (as a glTF embeds it).
TEST(ImageIo, PngChunkLongerThanTheFileIsRefused) {
    TempDir dir;
    std::string png = "\x89PNG\r\n\x1a\n";
    png += std::string("\x70\x71\x72\x73tEXt", 8) + std::string(10, 'a');
    const auto path = dir.write("big.png", png);
    for (int from_memory = 0; from_memory < 2; ++from_memory) {
        try {
            if (from_memory)
                read_image_bytes({reinterpret_cast<const unsigned char*>(png.data()), png.size()},
                                 "png", "embedded");
            else
                read_image(path);
            ADD_FAILURE() << "read";
        } catch (const ImageError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("PNG chunk 'tEXt' at byte 8 claims 1886483059 bytes; the file has 10"),
                      std::string::npos) << m;
        }
    }
}

// Images are read a band of rows at a time: one of several bands comes back texel for texel,
// alpha from the fourth channel included.
TEST(ImageIo, ImagesTallerThanABandReadWhole) {
    TempDir dir;
    Image img = gradient(611, 517);  // 2^18 floats a band: 107 rows of 611 RGBA texels
    write_image(dir.path() / "tall.exr", img);
    ImageData back = read_image(dir.path() / "tall.exr");
    ASSERT_EQ(back.width, 611);
    ASSERT_EQ(back.height, 517);
    for (int y = 0; y < 517; ++y)
        for (int x = 0; x < 611; ++x) ASSERT_EQ(back.texel(x, y), img.at(x, y)) << x << " " << y;
}

namespace {
// This process's peak resident memory in KiB since the last reset_peak_memory().
long peak_memory_kib() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0) return std::stol(line.substr(6));
    return -1;
}
void reset_peak_memory() { std::ofstream("/proc/self/clear_refs") << "5"; }
}  // namespace

// A header that claims more pixels than the file's data holds fails having touched memory for
// the rows it had, not for the claim: a 4096 x 4096 PNG cut after its first IDAT chunk (a
// claim of 200 MB as float RGB) fails within 64 MiB of peak memory.
TEST(ImageIo, PixelsEndingEarlyCostOnlyWhatTheFileHolds) {
    TempDir dir;
    Image img(4096, 4096);
    for (int y = 0; y < 4096; ++y)
        for (int x = 0; x < 4096; ++x) img.at(x, y) = Color(float((x * 7 + y * 13) % 256) / 255);
    write_image(dir.path() / "whole.png", img);
    std::ifstream in(dir.path() / "whole.png", std::ios::binary);
    const std::string png((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The signature and the chunks up to and including the first IDAT, then IEND.
    size_t at = 8;
    auto chunk_length = [&](size_t p) {
        return size_t((unsigned char)png[p]) << 24 | size_t((unsigned char)png[p + 1]) << 16 |
               size_t((unsigned char)png[p + 2]) << 8 | size_t((unsigned char)png[p + 3]);
    };
    while (png.compare(at + 4, 4, "IDAT") != 0) at += 12 + chunk_length(at);
    at += 12 + chunk_length(at);
    ASSERT_LT(at, png.size() / 4) << "the cut keeps most of the image";
    const std::string iend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
    const auto cut = dir.write("cut.png", png.substr(0, at) + iend);
    reset_peak_memory();
    const long before = peak_memory_kib();
    ASSERT_GT(before, 0);
    try {
        read_image(cut);
        ADD_FAILURE() << "read";
    } catch (const ImageError& e) {
        EXPECT_NE(std::string(e.what()).find(cut.string()), std::string::npos) << e.what();
    }
    const long grew = peak_memory_kib() - before;
    std::printf("peak memory grew %ld KiB reading %zu of %zu bytes\n", grew, at, png.size());
    EXPECT_LT(grew, 64 * 1024);
}

namespace {
std::string little_endian(int32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[i] = char((uint32_t(v) >> (8 * i)) & 0xff);
    return s;
}
// An OpenEXR file's magic number and version field, then the given attributes and the empty
// name that closes a header.
std::string exr_header(const std::string& attributes) {
    return std::string("\x76\x2f\x31\x01\x02\0\0\0", 8) + attributes + std::string(1, '\0');
}
}  // namespace

// OpenEXR allocates a string attribute's claimed size, and its tables from the data window,
// before reading them: both claims are checked against the file's size first.
TEST(ImageIo, ExrHeaderClaimsBeyondTheFileAreRefused) {
    TempDir dir;
    const auto long_attribute = dir.write(
        "long.exr", exr_header(std::string("comments\0string\0", 16) + little_endian(1 << 30) +
                               "abc"));
    const auto big_window = dir.write(
        "window.exr", exr_header(std::string("dataWindow\0box2i\0", 17) + little_endian(16) +
                                 little_endian(0) + little_endian(0) + little_endian(65535) +
                                 little_endian(65535)));
    const auto wide_window = dir.write(
        "wide.exr", exr_header(std::string("dataWindow\0box2i\0", 17) + little_endian(16) +
                               little_endian(-8) + little_endian(0) + little_endian(1 << 20) +
                               little_endian(0)));
    const std::pair<std::filesystem::path, std::string> cases[] = {
        {long_attribute,
         "OpenEXR attribute 'comments' at byte 8 claims 1073741824 bytes; the file has 4 after it"},
        {big_window, "the header claims 65536 x 65536 pixels, more than the limit of 67108864 texels"},
        {wide_window,
         "the header claims 1048585 x 1 pixels, more than an openexr file of 46 bytes can hold"},
    };
    for (const auto& [path, message] : cases) {
        try {
            read_image(path);
            ADD_FAILURE() << path;
        } catch (const ImageError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find(path.string() + ": "), std::string::npos) << m;
            EXPECT_NE(m.find(message), std::string::npos) << m;
        }
    }
}

// A header of one row and millions of columns: OpenEXR sizes its line buffers by the row (for
// up to 256 rows) and OpenImageIO converts through 256 rows, whatever the height, so such a
// row is refused before either reads (a fuzzer's 1 KB input asked for 7.6 GB this way). An
// OpenEXR header is checked from its channel list and data window, other formats from
// OpenImageIO's header.
TEST(ImageIo, RowsLongerThanTheLimitAreRefused) {
    TempDir dir;
    const std::pair<std::string, std::string> cases[] = {
        {"wide.exr", "the header claims rows of 100000 pixels x 12 bytes, more than the limit of "
                     "1048576 bytes a row"},
        {"wide.pfm", "rows of 100000 pixels x 3 channels take 1200000 bytes, more than the limit "
                     "of 1048576"},
    };
    for (const auto& [file, message] : cases) {
        const auto wide = dir.path() / file;
        write_image(wide, Image(100000, 1));
        try {
            read_image(wide);
            ADD_FAILURE() << file;
        } catch (const ImageError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find(wide.string() + ": " + message), std::string::npos) << m;
        }
        // As wide as the limit allows reads.
        const auto fits = dir.path() / ("fits-" + file);
        write_image(fits, Image(int(kMaxImageRowBytes / 12), 1));
        EXPECT_EQ(read_image(fits).width, int(kMaxImageRowBytes / 12)) << file;
    }
}
