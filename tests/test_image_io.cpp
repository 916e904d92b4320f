#include <gtest/gtest.h>

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
