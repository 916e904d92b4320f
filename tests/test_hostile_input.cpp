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

// PLY files are read by our own reader (loaders/ply_mesh.h). These inputs broke Assimp's PLY
// reader when it read them (found by tests/fuzz/fuzz_mesh: hangs, aborts, heap overruns,
// allocations of 8-44 GB); each is refused with its place, and nothing is allocated for a count
// before the rest of the file is known to hold it.
TEST(HostileInput, PlyFilesThatBrokeAssimpAreRefused) {
    using namespace std::string_literals;
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string face1 = "element face 1\nproperty list uchar int vertex_indices\n";
    const std::string vertices3 = "0 0 0\n1 0 0\n0 1 0\n";
    const std::string lists = "element vertex 3\n" + xyz +
                              "element face 1\nproperty list uint int vertex_indices\nend_header\n";
    const std::string binary_face0 =  // a face of 0 indices, then padding
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + xyz +
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n" +
        std::string(36, '\0') + "\x03\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00"s +
        std::string(13, '\0');
    const std::string binary_list =  // 2^30 indices announced, 3 given
        "ply\nformat binary_little_endian 1.0\n" + lists + std::string(36, '\0') +
        "\x00\x00\x00\x40\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00"s;
    const std::string hidden_element = "element 111111111111111101756035000 4\n";
    const struct {
        std::string file, message;
    } cases[] = {
        {"ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + face1 + "end_header\n" + vertices3 +
             "3 0 1 7\n",
         "face 0's vertex_indices names vertex 7 of 3 (line 13)"},
        {binary_face0, "PLY body: 12 bytes after the last element"},
        {"ply\nformat binary_little_endian 1.0\nelement 111111111111111111111111114 4\n"
         "property float x\nend_header\n" +
             std::string(16, '\0'),
         "PLY header has no vertex element"},
        {"ply\nformat binary_little_endian 1.0"s + '\0' + hidden_element +
             "property float x\nend_header\n" + std::string(16, '\0'),
         "PLY header, line 2: a control character in the header"},
        {"ply\nformat binary_little_endian 1.0\f" + hidden_element, "line 2: a control character"},
        {"ply\nformat binary_little_endian 1.0\r\rend_header\n", "line 2: a control character"},
        {"ply\nformat binary_little_endian 1.0\0\0end_header\n"s, "line 2: a control character"},
        {"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\0\0"
         "end_header\n\0\0\0\0"s,
         "line 4: a control character"},
        {"ply\nformat ascii 1.0\n" + lists + vertices3 +
             "2222222222222222222222222222222223 0 2 1\n",
         "'22222222222222222222222222222222' is not a number, in face 0's vertex_indices count "
         "(line 13)"},
        {"ply\nformat ascii 1.0\n" + lists + vertices3 + "-2147483647 0 2 1\n",
         "face 0's vertex_indices has -2147483647 items (line 13)"},
        {"ply\nformat ascii 1.0\n" + lists + vertices3 + "+2147483647 0 2 1\n",
         "the file ends before the 2147483647 items of face 0's vertex_indices (line 13)"},
        {binary_list, "the file ends before the 1073741824 items of face 0's vertex_indices"},
        {"ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + "element vertex 7\n" + xyz + face1 +
             "end_header\n",
         "PLY header, line 7: a second element 'vertex'"},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float\n",
         "PLY header, line 5: expected \"property TYPE NAME\""},
        {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property list uchar int idx\n" +
             face1 +
             "end_header\n0 0 0\n1 0 0\n"
             "99999999999999999999999 5 0\n3 0 1 2\n",
         "the vertex element has no x, y and z"},
        {"ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + face1 +
             "end_header\n0 0 0\n1 0 0\n"
             "1.5e+-3 0 0\n3 0 1 2\n",
         "'1.5e+-3' is not a number, in vertex 2's x (line 12)"},
        {"ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + face1 + "end_header\n" + vertices3,
         "PLY header announces 1 face records; the 1 bytes left hold fewer"},
        {"ply\nformat ascii 1.0\nelement vertex 3\n" + xyz + face1 + "end_header\n" + vertices3 +
             "3 0 1",
         "the file ends before the 3 items of face 0's vertex_indices (line 13)"},
        {"ply\nformat ascii 1.0\n", "PLY header has no end_header line"},
    };
    for (const auto& c : cases) {
        TempDir dir;
        dir.write("m.ply", c.file);
        expect_refused(dir, mesh_scene("m.ply"), c.message);
    }
}

// The forms a PLY writer may print still load: CRLF line ends, a blank line, a last line
// without its line end, signs, exponents, NaN and infinity (a triangle they touch is skipped),
// an element of neither vertices nor faces (skipped with a warning).
TEST(HostileInput, PlyInTheFormsWritersPrintLoads) {
    const std::string ok =
        "ply\nformat ascii 1.0\ncomment c\nelement vertex 3\nproperty float x\n"
        "property double y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nelement tristrips 1\n"
        "property list int int vertex_indices\nend_header\n"
        "0 -0.0 +0\n1.5e+0 0 .0\n-nan 1E-7 inf\n";
    TempDir dir;
    for (const std::string& text :
         {ok + "\n3 0 1 2\n2 0 1",
          std::regex_replace(ok, std::regex("\n"), "\r\n") + "3 0 1 2\r\n2 0 1"}) {
        dir.write("ok.ply", text);
        const fs::path p = dir.write("x.json", mesh_scene("ok.ply"));
        const CliResult r = run_guarded(dir, "info '" + p.string() + "'");
        EXPECT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.err.find("mesh '" + (dir.path() / "ok.ply").string() +
                             "' has an element 'tristrips' (1 records) that is skipped"),
                  std::string::npos)
            << r.err;
    }
    // A double beyond the float range is an infinite coordinate (its triangle skipped), not an
    // undefined conversion (UBSan's float-cast-overflow in `make sanitize`).
    dir.write("big.ply",
              "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\n"
              "property double y\nproperty double z\nelement face 2\n"
              "property list uchar int vertex_indices\nend_header\n"
              "0 0 0\n1 0 0\n0 1 0\n1e300 -1e300 0\n3 0 1 2\n3 1 3 2\n");
    const fs::path p = dir.write("x.json", mesh_scene("big.ply"));
    const CliResult r = run_guarded(dir, "info '" + p.string() + "'");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("1 degenerate triangles skipped"), std::string::npos) << r.err;
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

TEST(HostileInput, TruncatedBinaryPlyIsRefused) {
    TempDir dir;
    std::ifstream in(scene_path("bunny").parent_path() / "meshes" / "bunny.ply", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 10000u);
    dir.write("cut.ply", bytes.substr(0, bytes.size() - 5000));
    expect_refused(dir, mesh_scene("cut.ply"),
                   "PLY body: the file ends before the 3 items of face");
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
