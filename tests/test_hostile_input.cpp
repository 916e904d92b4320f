// Hostile and broken input, one test per class an audit found crashing or hanging the CLI:
// each must exit 2 with the file (and the place) named, write no image, and finish — the
// command runs under `timeout 20`, so a hang fails as exit 124 instead of stalling the suite.
// And the way out: failed writes exit non-zero, keep the previous file, leave no temporary.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <zlib.h>

#include <csignal>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

// Under `timeout 20`: a hang fails as exit 124 instead of stalling the suite.
CliResult run_guarded(const TempDir& dir, const std::string& args, const std::string& prefix = "") {
    return run_cli(dir, args, prefix, "timeout 20");
}

const char* kHead = R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"white": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}},
 "render": {"width": 16, "height": 16, "spp": 1}, )";

// Renders `scene` (written as x.json) and expects exit 2, the message to contain `expect`,
// and no image.
void expect_refused(const TempDir& dir, const std::string& scene, const std::string& expect) {
    fs::path p = dir.write("x.json", scene);
    fs::path out = dir.path() / "out.png";
    CliResult r = run_guarded(dir, "render '" + p.string() + "' -o '" + out.string() + "'");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(p.string()), std::string::npos) << "names the file: " << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

std::string mesh_scene(const std::string& file) {
    return std::string(kHead) + R"("objects": [{"type": "mesh", "file": ")" + file +
           R"(", "material": "white"}]})";
}

std::string nested(const std::string& open,
                   const std::string& inner,
                   const std::string& close,
                   int depth) {
    std::string s;
    for (int i = 0; i < depth; ++i) s += open;
    s += inner;
    for (int i = 0; i < depth; ++i) s += close;
    return s;
}

}  // namespace

TEST(HostileInput, DeeplyNestedArraysAreRefused) {
    TempDir dir;
    expect_refused(dir, std::string(kHead) + R"("objects": )" + nested("[", "", "]", 10000) + "}",
                   "x.json:3:");  // line:column of the level past the limit
    expect_refused(dir, std::string(kHead) + R"("objects": [)" + nested("[", "", "]", 10000) + "]}",
                   "nested deeper than 64 levels");
}

TEST(HostileInput, TexturesInsideTexturesAreRefused) {
    TempDir dir;
    std::string tex = nested(R"({"type": "checker", "scale": 1, "even": [0.5, 0.5, 0.5], "odd": )",
                             "[0.1, 0.1, 0.1]", "}", 10000);
    std::string scene = R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"white": {"type": "lambertian", "albedo": )" +
                        tex + R"(}}, "objects": []})";
    expect_refused(dir, scene, "nested deeper than 64 levels");
}

TEST(HostileInput, DeeplyNestedObjectsAreRefused) {
    TempDir dir;
    expect_refused(dir,
                   std::string(kHead) + R"("description": )" +
                       nested(R"({"a": )", "1", "}", 10000) + R"(, "objects": []})",
                   "nested deeper than 64 levels");
}

TEST(HostileInput, ThousandsOfNestedGroupsAreRefused) {
    TempDir dir;
    std::string groups = nested(
        R"({"type": "group", "objects": [)",
        R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"})", "]}", 6000);
    expect_refused(dir, std::string(kHead) + R"("objects": [)" + groups + "]}",
                   "nested deeper than 64 levels");
}

TEST(HostileInput, PlyFaceIndexBeyondTheVerticesIsRefused) {
    TempDir dir;
    dir.write("bad.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    expect_refused(dir, mesh_scene("bad.ply"), "/objects/0/file: cannot read mesh");
}

// Found by tests/fuzz/fuzz_mesh: a binary PLY face with no indices made an Assimp
// post-processing step assert (abort), and a broken PLY named .gltf hung Assimp's PLY reader,
// which Assimp picks by content when the extension's reader declines.
TEST(HostileInput, PlyFaceWithoutIndicesIsRefused) {
    TempDir dir;
    std::string ply =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 2\n"
        "property list uchar int vertex_indices\nend_header\n";
    ply += std::string(36, '\0');  // three vertices at the origin
    ply += std::string("\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 13);
    ply += std::string("\x00", 1) + std::string(12, '\0');  // a face of 0 indices, then padding
    dir.write("empty-face.ply", ply);
    expect_refused(dir, mesh_scene("empty-face.ply"), "has no vertices");
}

// Found by tests/fuzz/fuzz_mesh: Assimp reads a numeric first word of an element line as its
// count (wrapped to 32 bits), so "element 111111111111111111111111114 4" made it allocate 44 GB.
TEST(HostileInput, PlyElementWithANumericNameIsRefused) {
    TempDir dir;
    dir.write("numeric.ply",
              "ply\nformat binary_little_endian 1.0\nelement 111111111111111111111111114 4\n"
              "property float x\nend_header\n" +
                  std::string(16, '\0'));
    expect_refused(dir, mesh_scene("numeric.ply"), "PLY header: bad element line");
}

// Found by tests/fuzz/fuzz_mesh (seeds 3 and 20): Assimp's PLY reader also ends a header line
// at a NUL, a form feed or a carriage return, and some runs of those hang it or crash it; an
// element line hidden behind a NUL made it allocate 26 GB (out of memory under the sanitizers,
// std::bad_alloc otherwise). Run under a timeout: a hang fails as exit 124.
TEST(HostileInput, PlyHeaderWithControlCharactersIsRefused) {
    using namespace std::string_literals;
    const std::string hidden_element = "element 111111111111111101756035000 4\n";
    const std::string cases[] = {
        std::string("ply\nformat binary_little_endian 1.0") + '\0' + hidden_element +
            "property float x\nend_header\n" + std::string(16, '\0'),
        "ply\nformat binary_little_endian 1.0\f" + hidden_element +
            "property float x\nend_header\n" + std::string(16, '\0'),
        "ply\nformat binary_little_endian 1.0\r" + hidden_element +
            "property float x\nend_header\n" + std::string(16, '\0'),
        "ply\nformat binary_little_endian 1.0\0\0end_header\n"s,  // hung
        "ply\nformat binary_little_endian 1.0\r\rend_header\n",                   // hung
        "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\0\0"
        "end_header\n\0\0\0\0"s,  // crashed
    };
    for (const std::string& ply : cases) {
        TempDir dir;
        dir.write("control.ply", ply);
        expect_refused(dir, mesh_scene("control.ply"), "PLY header: control character");
    }
    // A header with Windows line ends is text.
    TempDir dir;
    dir.write("crlf.ply",
              "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\n"
              "property float y\r\nproperty float z\r\nelement face 1\r\n"
              "property list uchar int vertex_indices\r\nend_header\r\n"
              "0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2\r\n");
    fs::path p = dir.write("x.json", mesh_scene("crlf.ply"));
    CliResult r = run_guarded(dir, "render '" + p.string() + "' -o '" +
                                       (dir.path() / "out.png").string() + "'");
    EXPECT_EQ(r.code, 0) << r.err;
}

// Found by tests/fuzz/fuzz_mesh (seed 34): Assimp allocates what a face's list count asks for
// before reading its indices: 10^54 in an ASCII file ran the process out of memory (13 GB in 30
// s before it was stopped), 2^30 in a binary one took 8.5 GB and 15 s to be refused.
TEST(HostileInput, PlyListLongerThanTheFileIsRefused) {
    const std::string head =
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uint int vertex_indices\nend_header\n";
    TempDir dir;
    dir.write("ascii.ply", "ply\nformat ascii 1.0\n" + head +
                               "0 0 0\n1 0 0\n0 1 0\n2222222222222222222222222222222223 0 2 1\n");
    expect_refused(dir, mesh_scene("ascii.ply"), "PLY body: a list of");
    // A signed count of an unsigned type: "-2147483647" took 8.6 GB.
    for (const char* count : {"-2147483647", "+2147483647"}) {
        dir.write("signed.ply", "ply\nformat ascii 1.0\n" + head + "0 0 0\n1 0 0\n0 1 0\n" + count +
                                    " 0 2 1\n");
        expect_refused(dir, mesh_scene("signed.ply"),
                       "line 13: '" + std::string(count) +
                           "' is not a number the reader takes whole (an unsigned integer)");
    }
    std::string binary = "ply\nformat binary_little_endian 1.0\n" + head;
    binary += std::string(36, '\0');                                  // three vertices
    binary += std::string("\x00\x00\x00\x40", 4);                     // 2^30 indices ...
    binary += std::string("\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 12);  // ... or 3
    dir.write("binary.ply", binary);
    expect_refused(dir, mesh_scene("binary.ply"), "PLY body: a list of 1073741824 items");
}

// Found by tests/fuzz/fuzz_mesh (seed 29, without ASan): Assimp sizes its vertex array from the
// first `vertex` element and its faces from the first `face` or `tristrips` element, then fills
// them from every such element, so a second, longer one writes past the heap block (valgrind:
// "Invalid write ... 0 bytes after a block of size 36"; the release CLI aborted in free(), or
// loaded the file with its heap damaged).
TEST(HostileInput, PlyElementDeclaredTwiceIsRefused) {
    const std::string vertex3 =
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string vertex7 =
        "element vertex 7\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string face1 = "element face 1\nproperty list uchar int vertex_indices\n";
    const std::string face3 = "element face 3\nproperty list uchar int vertex_indices\n";
    const std::string strip1 = "element tristrips 1\nproperty list int int vertex_indices\n";
    const std::string vertices3 = "0 0 0\n1 0 0\n0 1 0\n";
    const std::string vertices7 = vertices3 + "0 0 1\n1 0 1\n0 1 1\n1 1 1\n";
    const struct {
        std::string header, body, message;
    } cases[] = {
        {vertex3 + vertex7 + face1, vertices3 + vertices7 + "3 0 1 2\n",
         "element 'vertex' at line 7 is declared again (first at line 3)"},
        {vertex3 + face1 + face3, vertices3 + "3 0 1 2\n3 0 1 2\n3 0 1 2\n3 0 1 2\n",
         "element 'face' at line 9 gives faces again (faces first at line 7)"},
        {vertex3 + strip1 + face3, vertices3 + "3 0 1 2\n3 0 1 2\n3 0 1 2\n3 0 1 2\n",
         "element 'face' at line 9 gives faces again (faces first at line 7)"},
    };
    for (const auto& c : cases) {
        TempDir dir;
        dir.write("twice.ply", "ply\nformat ascii 1.0\n" + c.header + "end_header\n" + c.body);
        expect_refused(dir, mesh_scene("twice.ply"), c.message);
    }
    // Either element alone loads.
    TempDir dir;
    dir.write("once.ply", "ply\nformat ascii 1.0\n" + vertex7 + face1 + "end_header\n" +
                              vertices7 + "3 0 1 2\n");
    const fs::path p = dir.write("x.json", mesh_scene("once.ply"));
    const CliResult r = run_guarded(dir, "info '" + p.string() + "'");
    EXPECT_EQ(r.code, 0) << r.err;
}

// Found by tests/fuzz/fuzz_mesh (seed 40): Assimp ends an element's properties at a property
// line it cannot parse ("property float", no name) and skips the property lines after it, and
// past the last line of an ASCII body it reads that line again for every element left, so a
// list count on it ("2222222222222222") made it allocate 21 GB in a minute.
TEST(HostileInput, PlyWithABadPropertyLineOrTooFewLinesIsRefused) {
    const std::string tail = "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    TempDir dir;
    dir.write("noname.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float\n"
              "property float z\n" +
                  tail + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n");
    expect_refused(dir, mesh_scene("noname.ply"),
                   "bad property line 'property float' at line 5");
    // Three vertices of x only, then the faces' lines are missing: the last line, read again
    // as a face, announces 2222222222222222 indices.
    dir.write("short.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n" + tail +
                  "0\n1\n2222222222222222\n");
    expect_refused(dir, mesh_scene("short.ply"),
                   "the file ends 2 element lines short of the 5 its header announces");
}

// Found by tests/fuzz/fuzz_mesh (seed 50): Assimp leaves a real number whose integer part
// overflows 64 bits where it is, so the next property reads the same digits, and a list count
// read from them wraps to 32 bits (a vertex line "<55 digits> 0 2": 13 GB in 15 s).
TEST(HostileInput, PlyRealTooLongForAssimpBeforeAListIsRefused) {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property list uchar int idx\nelement face 1\nproperty list uchar int vertex_indices\n"
        "end_header\n0 0 0\n1 0 0\n";
    TempDir dir;
    dir.write("long.ply", head + "99999999999999999999999 5 0\n3 0 1 2\n");
    expect_refused(dir, mesh_scene("long.ply"),
                   "line 12: '99999999999999999999999' is not a number the reader takes whole");
    // 2^64 - 1 fits Assimp's integer part: the line reads as x, y and an empty list.
    dir.write("fits.ply", head + "18446744073709551615 5 0\n3 0 1 2\n");
    expect_refused(dir, mesh_scene("fits.ply"), "reaches beyond +-1e7");
}

// Found by tests/fuzz/fuzz_mesh (seeds 50, 53; built without ASan): where an ASCII body's
// numbers or lines are not what the header's walk assumes, Assimp reads a list count from
// elsewhere than the check did: from where it stopped inside a number (it reads the next
// property from there: "1.5e+-3" leaves "-3"), past a NUL (a line end to Assimp), without a
// property line that follows no element (Assimp skips it), or past a last line cut short
// (Assimp reads on into its buffer). The fuzzer's inputs took 13-18 GB in 15-20 s each in the
// release CLI.
TEST(HostileInput, PlyBodyAssimpWouldMisreadIsRefused) {
    const std::string vertex =
        "element vertex 3\nproperty float x\nproperty float y\nproperty list int int idx\n";
    const std::string face = "element face 1\nproperty list uchar int vertex_indices\n";
    const std::string faces = "3 0 1 2\n";
    const struct {
        std::string header, body, message;
    } cases[] = {
        {"element vertex 3\nproperty float x\nproperty list int int idx\n" + face,
         "0 0\n1 0\n1.5e+-3 0\n" + faces,
         "line 11: '1.5e+-3' is not a number the reader takes whole (a real)"},
        {vertex + face, "0 0 0\n1 0 0\n0 1 0" + std::string(1, '\0') + " 7\n" + faces,
         "PLY body: control character 0x00 at byte"},
        {vertex + "comment x\nproperty float z\n" + face, "",
         "property line 'property float z' at line 8 does not follow an element line"},
        {vertex + face + "property float quality\n", "0 0 0\n1 0 0\n0 1 0\n3 0 1 2",
         "line 14: the file's last line is cut short"},
        {vertex + face, "0 0 0\n1 0 0\n0 1 0\n", "the file ends 1 element lines short of the 4"},
    };
    TempDir dir;
    for (const auto& c : cases) {
        dir.write("misread.ply", "ply\nformat ascii 1.0\n" + c.header + "end_header\n" + c.body);
        expect_refused(dir, mesh_scene("misread.ply"), c.message);
    }
    // What Assimp reads as the walk does still loads: a blank line between elements (in a file
    // of "\n" line ends: in "\r\n" ones Assimp reads it as an element), CRLF line ends, a last
    // line without its line end, and the forms of numbers writers print.
    const std::string ok =
        "ply\nformat ascii 1.0\ncomment c\nelement vertex 3\nproperty float x\n"
        "property double y\nproperty float z\n" + face + "end_header\n"
        "0 -0.0 +0\n1.5e+0 0 .0\n-nan 1E-7 inf\n";
    for (const std::string& text : {ok + "\n3 0 1 2", std::regex_replace(ok, std::regex("\n"), "\r\n") + "3 0 1 2"}) {
        dir.write("ok.ply", text);
        const fs::path p = dir.write("x.json", mesh_scene("ok.ply"));
        const CliResult r = run_guarded(dir, "info '" + p.string() + "'");
        EXPECT_EQ(r.code, 0) << r.err;
    }
}

TEST(HostileInput, BrokenPlyUnderAnotherExtensionIsRefused) {
    TempDir dir;
    dir.write("m.gltf", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n");
    expect_refused(dir, mesh_scene("m.gltf"), "glTF JSON:1:1: invalid JSON");
    // A .glb that is none: its header is read before any reader is tried.
    dir.write("m.glb", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n");
    expect_refused(dir, mesh_scene("m.glb"), "not a binary glTF 2.0 file (header)");
}

// Found by tests/fuzz/fuzz_mesh: Assimp's OFF reader allocates what the header asks for.
TEST(HostileInput, OffHeaderClaimingBillionsOfVerticesIsRefused) {
    TempDir dir;
    dir.write("big.off", "OFF\n11111111111 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n");
    expect_refused(dir, mesh_scene("big.off"), "OFF header announces 11111111111 elements");
}

TEST(HostileInput, PlyWithOnlyItsFirstHeaderLineIsRefused) {
    TempDir dir;
    dir.write("head.ply", "ply\nformat ascii 1.0\n");
    expect_refused(dir, mesh_scene("head.ply"), "no end_header");
}

TEST(HostileInput, TruncatedBinaryPlyIsRefused) {
    TempDir dir;
    std::ifstream in(scene_path("bunny").parent_path() / "meshes" / "bunny.ply", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 10000u);
    dir.write("cut.ply", bytes.substr(0, bytes.size() - 5000));
    expect_refused(dir, mesh_scene("cut.ply"), "truncated");
}

TEST(HostileInput, MeshPathThatIsAFifoIsRefused) {
    TempDir dir;
    ASSERT_EQ(::mkfifo((dir.path() / "fifo.obj").c_str(), 0600), 0);
    expect_refused(dir, mesh_scene("fifo.obj"), "not a regular file (a FIFO)");
}

TEST(HostileInput, TexturePathThatIsADeviceIsRefused) {
    TempDir dir;
    std::string scene = R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"tex": {"type": "lambertian", "albedo": {"type": "image", "file": "/dev/zero"}}},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "tex"}]})";
    expect_refused(
        dir, scene,
        "/materials/tex/albedo/file: /dev/zero: cannot read image: not a regular file (a device)");
}

TEST(HostileInput, DeviceAsTheSceneFileIsRefused) {
    TempDir dir;
    fs::path out = dir.path() / "out.png";
    CliResult r = run_guarded(dir, "render /dev/zero -o '" + out.string() + "'");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("/dev/zero: cannot open scene file: not a regular file (a device)"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out));
}

// A valid PNG whose header claims 100000 x 100000 pixels (chunk CRCs computed with zlib).
TEST(HostileInput, ImageClaimingEnormousDimensionsIsRefusedFromItsHeader) {
    TempDir dir;
    auto chunk = [](const std::string& type, const std::string& data) {
        auto be32 = [](uint32_t v) {
            return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
        };
        std::string body = type + data;
        uint32_t crc = crc32(0, reinterpret_cast<const Bytef*>(body.data()), body.size());
        return be32(uint32_t(data.size())) + body + be32(crc);
    };
    std::string ihdr =
        std::string("\x00\x01\x86\xa0\x00\x01\x86\xa0", 8) + std::string("\x08\x02\x00\x00\x00", 5);
    std::string png = std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) +
                      chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) +
                      chunk("IEND", "");
    dir.write("huge.png", png);
    std::string scene = R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"tex": {"type": "lambertian", "albedo": {"type": "image", "file": "huge.png"}}},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "tex"}]})";
    expect_refused(dir, scene, "image of 100000 x 100000 x 3 channels exceeds the limit");
}

TEST(HostileInput, ScalesWhoseProductOverflowsAreRefused) {
    TempDir dir;
    std::string steps;
    for (int i = 0; i < 6; ++i) steps += std::string(i ? ", " : "") + R"({"scale": 1e7})";
    expect_refused(dir,
                   std::string(kHead) + R"("objects": [{"type": "sphere", "center": [0, 0, 0],
 "radius": 1, "material": "white", "transform": [)" +
                       steps + "]}]}",
                   "/objects/0/transform/1: the transform up to this step scales beyond");
    // The same overflow spread over nested groups is caught where the product is formed.
    std::string inner =
        R"({"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"})";
    for (int i = 0; i < 6; ++i)
        inner = R"({"type": "group", "transform": [{"scale": 1e7}], "objects": [)" + inner + "]}";
    expect_refused(dir, std::string(kHead) + R"("objects": [)" + inner + "]}",
                   "the composed transform (with its groups') scales beyond");
}

TEST(HostileInput, DegenerateCameraIsRefused) {
    TempDir dir;
    expect_refused(dir, R"({"camera": {"look_from": [0, 0, 0], "look_at": [0, 0, 1e-30]},
 "materials": {"white": {"type": "lambertian", "albedo": [0.5, 0.5, 0.5]}}, "objects": []})",
                   "/camera/look_at: look_at must differ from look_from");
}

// ---- the way out --------------------------------------------------------------------------

TEST(HostileOutput, OutputThatIsADirectoryIsRefusedBeforeRendering) {
    TempDir dir;
    fs::create_directories(dir.path() / "out.png");
    CliResult r = run_guarded(dir, "render '" + scene_path("cornell").string() + "' -o '" +
                                       (dir.path() / "out.png").string() + "'");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("out.png: cannot write: is a directory"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("spp:"), std::string::npos) << "no render ran: " << r.err;
}

TEST(HostileOutput, UnwritableFolderIsRefusedBeforeRendering) {
    TempDir dir;
    // /proc refuses new files even to root, so this holds whoever runs the tests.
    CliResult r =
        run_guarded(dir, "render '" + scene_path("cornell").string() + "' -o /proc/x.png");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("/proc/x.png: cannot write in folder '/proc'"), std::string::npos)
        << r.err;
}

// A full disk, injected with the file-size limit (write() then fails with EFBIG, as it fails
// with ENOSPC on a full disk): every format must fail, keep the previous file and leave no
// temporary file behind.
TEST(HostileOutput, FailedWriteKeepsThePreviousFileAndLeavesNoTemporary) {
    for (const char* ext : {"png", "jpg", "exr", "hdr", "pfm"}) {
        TempDir dir;
        fs::path out = dir.path() / (std::string("out.") + ext);
        std::ofstream(out) << "previous";
        CliResult r =
            run_guarded(dir,
                        "render '" + scene_path("cornell").string() +
                            "' --width 128 --height 128 --spp 1 -o '" + out.string() + "'",
                        "trap '' XFSZ; ulimit -f 4;");  // 4 KiB
        EXPECT_EQ(r.code, 1) << ext << ": " << r.err;
        EXPECT_NE(r.err.find("cannot write: File too large"), std::string::npos) << r.err;
        std::stringstream kept;
        kept << std::ifstream(out).rdbuf();
        EXPECT_EQ(kept.str(), "previous") << ext;
        size_t files = 0;
        for (const auto& e : fs::directory_iterator(dir.path()))
            if (e.path().filename() != "stderr" && e.path().filename() != "stdout") ++files;
        EXPECT_EQ(files, 1u) << ext << ": a temporary file was left behind";
    }
}

// A signal during the write: exceeding the file-size limit raises SIGXFSZ in the middle of
// write(), which kills the process; the temporary file must be gone and the previous file kept.
TEST(HostileOutput, SignalDuringTheWriteLeavesNoTemporary) {
    TempDir dir;
    fs::path out = dir.path() / "out.png";
    std::ofstream(out) << "previous";
    CliResult r = run_guarded(dir,
                              "render '" + scene_path("cornell").string() +
                                  "' --width 128 --height 128 --spp 1 -o '" + out.string() + "'",
                              "ulimit -f 4;");
    EXPECT_EQ(r.code, 128 + SIGXFSZ) << "killed by SIGXFSZ: " << r.err;
    std::stringstream kept;
    kept << std::ifstream(out).rdbuf();
    EXPECT_EQ(kept.str(), "previous");
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir.path()))
        if (e.path().filename() != "stderr" && e.path().filename() != "stdout") ++files;
    EXPECT_EQ(files, 1u) << "a temporary file was left behind";
}

TEST(HostileOutput, RunningOutOfMemoryIsAnErrorNotACrash) {
    if (kUnderAddressSanitizer)
        GTEST_SKIP() << "AddressSanitizer reserves terabytes of shadow memory: no `ulimit -v` fits";
    TempDir dir;
    fs::path out = dir.path() / "big.exr";
    // 16384 x 8192 pixels: the film alone needs 6.5 GiB; 3 GiB of address space is not enough.
    CliResult r = run_guarded(dir,
                              "render '" + scene_path("cornell").string() +
                                  "' --width 16384 --height 8192 --spp 1 --threads 1 -o '" +
                                  out.string() + "'",
                              "ulimit -v 3000000;");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("out of memory rendering 16384 x 8192"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

// The address space (KiB, for `ulimit -v`) in which a tiny render just runs: the shared
// libraries alone take about 460 MB, which differs between machines. 0 if none up to 2 GB.
long tiny_render_kib(const TempDir& dir) {
    for (long kib = 300000; kib <= 2000000; kib += 20000) {
        CliResult r = run_guarded(dir,
                                  "render '" + scene_path("cornell").string() +
                                      "' --width 8 --height 8 --spp 1 --threads 2 -o '" +
                                      (dir.path() / "tiny.png").string() + "'",
                                  "ulimit -v " + std::to_string(kib) + ";");
        if (r.code == 0) return kib;
    }
    return 0;
}

// Out of memory at any point of loading or rendering (a sweep of address-space limits above
// what a tiny render needs): exit 0 with an image, or exit 2 naming what ran out — never an
// abort. Before: nlohmann's JSON destructor allocates (its flattening stack), so a scene file
// with a large array aborted (exit 134) at every limit from 630 MB to 1 GB here, and a mesh
// that ran out said "std::bad_alloc".
TEST(HostileOutput, RunningOutOfMemoryAnywhereNamesWhatRanOut) {
    if (kUnderAddressSanitizer)
        GTEST_SKIP() << "AddressSanitizer reserves terabytes of shadow memory: no `ulimit -v` fits";
    TempDir dir;
    const long base = tiny_render_kib(dir);
    ASSERT_GT(base, 0) << "no `ulimit -v` up to 2 GB lets a tiny render run";
    // A scene whose description is an array of 12 million zeros (24 MB): parsed, it takes
    // 12e6 x 16 bytes plus the vector's growth.
    const fs::path big = dir.path() / "big.json";
    {
        std::ofstream f(big);
        f << R"({"description": [0)";
        for (int i = 1; i < 12000000; ++i) f << ",0";
        f << "]}";
    }
    struct Case {
        fs::path scene;
        std::vector<long> extra_kib;
    };
    const std::vector<Case> cases = {
        {scene_path("dragon"), {0, 40000, 80000, 120000, 160000, 200000}},
        {scene_path("materials"), {0, 40000, 80000, 120000}},
        {big, {0, 100000, 200000, 300000, 400000, 500000}},
    };
    int out_of_memory = 0;
    for (const Case& c : cases) {
        for (long extra : c.extra_kib) {
            const fs::path out = dir.path() / "out.png";
            fs::remove(out);
            const long kib = base + extra;
            CliResult r = run_guarded(dir,
                                      "render '" + c.scene.string() +
                                          "' --width 64 --height 64 --spp 1 --threads 2 -o '" +
                                          out.string() + "'",
                                      "ulimit -v " + std::to_string(kib) + ";");
            SCOPED_TRACE(c.scene.filename().string() + " under ulimit -v " + std::to_string(kib));
            ASSERT_TRUE(r.code == 0 || r.code == 2) << "exit " << r.code << ": " << r.err;
            EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
            EXPECT_EQ(fs::exists(out), r.code == 0) << r.err;
            if (r.code == 2 && r.err.find("out of memory") != std::string::npos) {
                ++out_of_memory;
                // What ran out: the scene file, a mesh or image with its place, the BVH, the
                // render; never the bare words.
                EXPECT_NE(r.err.find("out of memory "), std::string::npos) << r.err;
                EXPECT_EQ(r.err.find("out of memory\n"), std::string::npos) << r.err;
            } else if (r.code == 2) {
                // The big scene, parsed in full, fails on its description.
                EXPECT_EQ(c.scene, big) << r.err;
                EXPECT_NE(r.err.find("/description: expected a string"), std::string::npos)
                    << r.err;
            }
        }
    }
    EXPECT_GE(out_of_memory, 3) << "the sweep should run out of memory in places";
}
