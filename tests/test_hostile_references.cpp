// Hostile input one level down: the files a mesh pulls in (an OBJ's MTL, a glTF's buffers),
// glTF containers and hierarchies built to overflow Assimp, image headers that claim more
// pixels than their file holds, and output names that would destroy the inputs. Each runs the
// CLI under `timeout 20`: exit 2 with the file named, no image, no hang.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "cli_run.h"

namespace fs = std::filesystem;

namespace {

CliResult run_guarded(const TempDir& dir, const std::string& args, const std::string& prefix = "") {
    return run_cli(dir, args, prefix, "timeout 20");
}

// Renders a scene holding the mesh `file` (relative to the scene's folder, `dir`) with the
// file's own materials; expects exit 2, `expect` in the message, and no image.
void expect_mesh_refused(const TempDir& dir, const std::string& file, const std::string& expect) {
    const fs::path scene = dir.write(
        "x.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "render": {"width": 16, "height": 16, "spp": 1},
 "objects": [{"type": "mesh", "file": ")" +
                      file + R"(", "materials": "file"}]})");
    const fs::path out = dir.path() / "out.png";
    CliResult r = run_guarded(dir, "render '" + scene.string() + "' -o '" + out.string() + "'");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(scene.string()), std::string::npos) << "names the scene: " << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
}

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n";

// A one-triangle glTF whose buffer is at `uri`, with `extra` members and the nodes `nodes`.
std::string gltf_with_buffer(const std::string& uri,
                             const std::string& extra = "",
                             const std::string& nodes = R"({"mesh": 0})") {
    return R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [)" + nodes +
           R"(],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [1, 1, 0]}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "buffers": [{"uri": ")" +
           uri + R"(", "byteLength": 36}])" + extra + "}";
}

uint32_t le(uint32_t v) { return v; }  // the platforms we build for are little-endian

std::string u32(uint32_t v) {
    v = le(v);
    return std::string(reinterpret_cast<const char*>(&v), 4);
}

}  // namespace

TEST(HostileInput, MtlThatIsAFifoIsRefusedWithoutHanging) {
    TempDir dir;
    dir.write("m.obj", std::string("mtllib pipe.mtl\n") + kTriangleObj);
    ASSERT_EQ(::mkfifo((dir.path() / "pipe.mtl").c_str(), 0600), 0);
    expect_mesh_refused(dir, "m.obj", "pipe.mtl: not a regular file (a FIFO)");
}

TEST(HostileInput, GltfBufferThatIsAFifoIsRefusedWithoutHanging) {
    TempDir dir;
    dir.write("m.gltf", gltf_with_buffer("pipe.bin"));
    ASSERT_EQ(::mkfifo((dir.path() / "pipe.bin").c_str(), 0600), 0);
    expect_mesh_refused(dir, "m.gltf", "pipe.bin: not a regular file (a FIFO)");
}

TEST(HostileInput, MeshReferencesOutsideTheMeshFolderAreRefused) {
    TempDir dir;
    dir.write("secret.bin", std::string(36, '\0'));
    dir.write("meshes/m.gltf", gltf_with_buffer("../secret.bin"));
    expect_mesh_refused(dir, "meshes/m.gltf", "secret.bin: outside the folder");
    dir.write("secret.mtl", "newmtl m\nKd 1 1 1\n");
    dir.write("meshes/m.obj", std::string("mtllib ../secret.mtl\n") + kTriangleObj);
    expect_mesh_refused(dir, "meshes/m.obj", "secret.mtl: outside the folder");
}

TEST(HostileInput, MissingMtlIsAWarningNamingIt) {
    TempDir dir;
    dir.write("m.obj", std::string("mtllib gone.mtl\n") + kTriangleObj);
    const fs::path scene = dir.write(
        "x.json", R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "render": {"width": 8, "height": 8, "spp": 1},
 "objects": [{"type": "mesh", "file": "m.obj", "materials": "file"}]})");
    CliResult r = run_guarded(dir, "render '" + scene.string() + "' -o '" +
                                       (dir.path() / "out.png").string() + "'");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("mesh '" + (dir.path() / "m.obj").string() + "' names "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("gone.mtl: no such file"), std::string::npos) << r.err;
}

// 444 bytes whose JSON chunk claims 0xFFFFFFF0 bytes: Assimp allocated that much first.
TEST(HostileInput, GlbChunkLongerThanTheFileIsRefused) {
    TempDir dir;
    const std::string json = gltf_with_buffer("data:application/octet-stream;base64,AAAA");
    std::string glb = "glTF" + u32(2) + u32(444) + u32(0xFFFFFFF0u) + "JSON" + json;
    glb.resize(444, ' ');
    dir.write("m.glb", glb);
    expect_mesh_refused(dir, "m.glb", "binary glTF: the first chunk is no JSON chunk within the file");
    std::string body = json + std::string((4 - json.size() % 4) % 4, ' ');
    std::string two = "glTF" + u32(2) + u32(uint32_t(12 + 8 + body.size() + 8)) +
                      u32(uint32_t(body.size())) + "JSON" + body + u32(0xFFFFFFF0u) + "BIN";
    two.push_back('\0');
    dir.write("two.glb", two);
    expect_mesh_refused(dir, "two.glb", "claims 4294967280 bytes, beyond the file's length");
}

TEST(HostileInput, GltfNodeChainsAndDeepJsonAreRefusedBeforeAssimp) {
    TempDir dir;
    const std::string data = "data:application/octet-stream;base64,AAAA";
    // 20,000 nodes, each the parent of the next: Assimp recursed through them and overflowed
    // its stack. The same chain closed into a cycle is refused as one.
    auto chain = [](bool cycle) {
        std::string nodes = R"({"mesh": 0, "children": [1]})";
        for (int i = 1; i < 20000; ++i)
            nodes += i + 1 < 20000 ? R"(, {"children": [)" + std::to_string(i + 1) + "]}"
                     : cycle       ? R"(, {"children": [0]})"
                                   : ", {}";
        return nodes;
    };
    dir.write("deep.gltf", gltf_with_buffer(data, "", chain(false)));
    expect_mesh_refused(dir, "deep.gltf", "nested deeper than 1024 nodes");
    dir.write("cycle.gltf", gltf_with_buffer(data, "", chain(true)));
    expect_mesh_refused(dir, "cycle.gltf", "/nodes: the hierarchy has a cycle");
    const std::string extras = std::string(200000, '[') + std::string(200000, ']');
    dir.write("extras.gltf", gltf_with_buffer(data, ", \"extras\": " + extras));
    expect_mesh_refused(dir, "extras.gltf", "nested deeper than 64 levels");
}

// ~100-byte headers that claim 8000 x 8000 pixels.
TEST(HostileInput, ImageHeadersClaimingMorePixelsThanTheFileHoldsAreRefused) {
    TempDir dir;
    dir.write("big.ppm", "P6\n8000 8000\n255\n" + std::string(64, '\x80'));
    dir.write("big.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8000 +X 8000\n" +
                             std::string(40, '\x02'));
    for (const char* name : {"big.ppm", "big.hdr"}) {
        const fs::path scene = dir.write(
            "x.json", std::string(R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"tex": {"type": "lambertian", "albedo": {"type": "image", "file": ")") +
                          name + R"("}}},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "tex"}]})");
        const fs::path out = dir.path() / "out.png";
        CliResult r = run_guarded(dir, "render '" + scene.string() + "' -o '" + out.string() + "'",
                                  // A memory bound, where the build allows one.
                                  kUnderAddressSanitizer ? "" : "ulimit -v 1500000;");
        EXPECT_EQ(r.code, 2) << name << ": " << r.err;
        EXPECT_NE(r.err.find(std::string(name) + ": the header claims 8000 x 8000 pixels"),
                  std::string::npos)
            << r.err;
        EXPECT_FALSE(fs::exists(out));
    }
}

// Outputs must not be the scene or each other; the scene is left as it was.
TEST(HostileOutput, OutputsNamingTheSceneOrEachOtherAreRefused) {
    TempDir dir;
    const fs::path scene = dir.path() / "victim.json";
    fs::copy_file(scene_path("cornell"), scene);
    std::stringstream before;
    before << std::ifstream(scene).rdbuf();
    const std::string base =
        "render '" + scene.string() + "' --width 16 --height 16 --spp 1 ";
    const std::string img = (dir.path() / "x.exr").string();
    const struct {
        std::string args, expect;
    } cases[] = {
        {"-o '" + img + "' --film '" + scene.string() + "'", "is the scene file"},
        {"-o '" + img + "' --film '" + dir.path().string() + "/./victim.json'",
         "is the scene file"},
        {"-o '" + img + "' --variance '" + img + "'", "--variance and -o/--output name the same"},
        {"-o '" + img + "' --film '" + img + "'", "--film and -o/--output name the same"},
        {"-o '" + scene.string() + ".exr' --variance '" + scene.string() + ".exr'",
         "name the same file"},
    };
    for (const auto& c : cases) {
        CliResult r = run_guarded(dir, base + c.args);
        EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
        EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    }
    std::stringstream after;
    after << std::ifstream(scene).rdbuf();
    EXPECT_EQ(before.str(), after.str());
    EXPECT_FALSE(fs::exists(img));
}

// A name the file system cannot hold fails before the render, not after it.
TEST(HostileOutput, OutputNamesTooLongAreRefusedBeforeRendering) {
    TempDir dir;
    const std::string name = std::string(246, 'a') + ".exr";  // 250 characters
    for (const std::string option : {"-o", "--variance", "--film"}) {
        const std::string other = option == "-o" ? "" : " -o '" + (dir.path() / "x.exr").string() + "'";
        CliResult r = run_guarded(dir, "render '" + scene_path("cornell").string() +
                                           "' --width 16 --height 16 --spp 1 " + option + " '" +
                                           (dir.path() / name).string() + "'" + other);
        EXPECT_EQ(r.code, 2) << option << ": " << r.err;
        EXPECT_NE(r.err.find("File name too long"), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find("samples"), std::string::npos) << "no render ran: " << r.err;
    }
}

// Checkpoints that cannot be written (the file-size limit stands for a full disk) are warnings;
// the image is still written, and the exit code says the film is not.
TEST(HostileOutput, FailingFilmWritesCostNeitherTheRenderNorTheImage) {
    TempDir dir;
    const fs::path out = dir.path() / "x.exr", film = dir.path() / "x.film";
    CliResult r = run_guarded(
        dir,
        "render '" + scene_path("cornell").string() +
            "' --width 96 --height 96 --spp 48 --checkpoint-every 0.02 --film '" +
            film.string() + "' -o '" + out.string() + "'",
        "trap '' XFSZ; ulimit -f 300;");  // 300 KiB: the image fits, the film (470 KiB) not
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find("checkpoint not written"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the image is written, the film is not"), std::string::npos) << r.err;
    EXPECT_TRUE(fs::exists(out));
    EXPECT_FALSE(fs::exists(film));
    size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir.path()))
        if (e.path().filename().string().starts_with(".")) ++files;
    EXPECT_EQ(files, 0u) << "a temporary file was left behind";
}

// Work Assimp would spend out of proportion to a small file: thousands of material names, a
// polygon whose triangulation is quadratic in its vertices.
TEST(HostileInput, ObjWorkOutOfProportionToItsSizeIsRefused) {
    TempDir dir;
    std::string names = kTriangleObj;
    for (int i = 0; i < 5000; ++i) names += "usemtl m" + std::to_string(i) + "\nf 1 2 3\n";
    dir.write("names.obj", names);
    expect_mesh_refused(dir, "names.obj", "more than 4096 material names (usemtl)");
    const int n = 8200;  // n^2 just over 2^26
    std::string polygon, face = "f";
    for (int i = 0; i < n; ++i) {
        polygon += "v " + std::to_string(std::cos(i * 6.283185 / n)) + " " +
                   std::to_string(std::sin(i * 6.283185 / n)) + " 0\n";
        face += " " + std::to_string(i + 1);
    }
    dir.write("polygon.obj", polygon + face + "\n");
    expect_mesh_refused(dir, "polygon.obj", "polygons too large to triangulate");
}

// The smaller messages: each names the file, the place and the reason.
TEST(HostileInput, MessagesNameThePlaceAndTheReason) {
    TempDir dir;
    const std::string head = R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"t": {"type": "lambertian", "albedo": {"type": "image", "file": )";
    const std::string tail =
        R"(}}}, "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "t"}]})";
    auto info = [&](const std::string& scene) {
        const fs::path p = dir.write("x.json", scene);
        return run_guarded(dir, "info '" + p.string() + "'");
    };
    CliResult overflow = info("{\n \"camera\": {\"look_from\": [0, 0, -5], \"look_at\": [0, 0, 1e999]}}");
    EXPECT_EQ(overflow.code, 2);
    EXPECT_NE(overflow.err.find("x.json:2:56: invalid JSON: number overflow parsing '1e999'"),
              std::string::npos)
        << overflow.err;
    fs::create_symlink("loop1.png", dir.path() / "loop2.png");
    fs::create_symlink("loop2.png", dir.path() / "loop1.png");
    CliResult loop = info(head + R"("loop1.png")" + tail);
    EXPECT_EQ(loop.code, 2);
    EXPECT_NE(loop.err.find("loop1.png': Too many levels of symbolic links"), std::string::npos)
        << loop.err;
    dir.write("x.png", "not read");
    CliResult nul = info(head + R"("x.png\u0000.jpg")" + tail);
    EXPECT_EQ(nul.code, 2);
    EXPECT_NE(nul.err.find("/materials/t/albedo/file: a file name cannot hold a NUL character"),
              std::string::npos)
        << nul.err;
}

// A resume asking for fewer samples than the film holds renders nothing, and says so.
TEST(HostileOutput, ResumingToFewerSamplesThanTheFilmHoldsIsSaid) {
    TempDir dir;
    const std::string film = (dir.path() / "x.film").string(), out = (dir.path() / "x.exr").string();
    const std::string render = "render '" + scene_path("cornell").string() +
                               "' --width 16 --height 16 -o '" + out + "' ";
    ASSERT_EQ(run_guarded(dir, render + "--spp 4 --film '" + film + "'").code, 0);
    CliResult r = run_guarded(dir, render + "--spp 2 --resume '" + film + "'");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("holds 4 samples per pixel, more than --spp 2; nothing is rendered"),
              std::string::npos)
        << r.err;
}

// --asset-root confines every file a scene reads, whatever names it, with symbolic links
// resolved; without it a scene reads beside itself as before, but a mesh's own references stay
// in the mesh's folder.
TEST(HostileInput, AnAssetRootConfinesEveryFileTheSceneReads) {
    TempDir dir;
    const fs::path root = dir.path() / "root";
    dir.write("outside/tex.ppm", "P3\n1 1\n255\n200 100 50\n");
    dir.write("root/tex.ppm", "P3\n1 1\n255\n200 100 50\n");
    fs::create_symlink(dir.path() / "outside" / "tex.ppm", root / "link.ppm");
    auto scene_with_texture = [&](const std::string& file) {
        return std::string(R"({"camera": {"look_from": [0, 0, -5], "look_at": [0, 0, 0]},
 "materials": {"t": {"type": "lambertian", "albedo": {"type": "image", "file": ")") +
               file + R"("}}},
 "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "t"}]})";
    };
    auto info = [&](const std::string& scene_file, const std::string& extra) {
        return run_guarded(dir, "info '" + (dir.path() / scene_file).string() + "' " + extra);
    };
    const std::string confined = "--asset-root '" + root.string() + "'";
    dir.write("root/inside.json", scene_with_texture("tex.ppm"));
    EXPECT_EQ(info("root/inside.json", confined).code, 0);
    dir.write("root/escape.json", scene_with_texture("../outside/tex.ppm"));
    EXPECT_EQ(info("root/escape.json", "").code, 0) << "no root: as before";
    CliResult escape = info("root/escape.json", confined);
    EXPECT_EQ(escape.code, 2);
    EXPECT_NE(escape.err.find("/materials/t/albedo/file: " + root.string() +
                              "/../outside/tex.ppm: outside the asset root " + root.string()),
              std::string::npos)
        << escape.err;
    dir.write("root/link.json", scene_with_texture("link.ppm"));
    CliResult link = info("root/link.json", confined);
    EXPECT_EQ(link.code, 2);
    EXPECT_NE(link.err.find("link.ppm: outside the asset root"), std::string::npos) << link.err;
    dir.write("outside/scene.json", scene_with_texture("tex.ppm"));
    CliResult scene = info("outside/scene.json", confined);
    EXPECT_EQ(scene.code, 2);
    EXPECT_NE(scene.err.find("scene.json: outside the asset root"), std::string::npos)
        << scene.err;
    // Includes of the other formats.
    dir.write("outside/part.xml", R"(<scene version="3.0.0"/>)");
    dir.write("root/a.xml", R"(<scene version="3.0.0"><include filename="../outside/part.xml"/>
<shape type="sphere"><bsdf type="diffuse"/></shape></scene>)");
    CliResult xml = info("root/a.xml", confined);
    EXPECT_EQ(xml.code, 2);
    EXPECT_NE(xml.err.find("outside the asset root"), std::string::npos) << xml.err;
    dir.write("outside/part.pbrt", "\n");
    dir.write("root/a.pbrt", "WorldBegin\nInclude \"../outside/part.pbrt\"\nShape \"sphere\"\n");
    CliResult pbrt = info("root/a.pbrt", confined);
    EXPECT_EQ(pbrt.code, 2);
    EXPECT_NE(pbrt.err.find("outside the asset root"), std::string::npos) << pbrt.err;
}

// A mesh's texture (map_Kd) is one of its own references: it may not leave the mesh's folder.
TEST(HostileInput, MeshTexturesOutsideTheMeshFolderAreRefused) {
    TempDir dir;
    dir.write("tex.ppm", "P3\n1 1\n255\n200 100 50\n");
    dir.write("meshes/m.mtl", "newmtl m\nKd 1 1 1\nmap_Kd ../tex.ppm\n");
    dir.write("meshes/m.obj", std::string("mtllib m.mtl\nvt 0 0\nvt 1 0\nvt 0 1\n") +
                                  "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1/1 2/2 3/3\n");
    expect_mesh_refused(dir, "meshes/m.obj", "tex.ppm': outside the folder");
}

// Assimp 5.2 segfaults (a write through a null material) on a texture statement before the
// first `newmtl` of a material library, also when the OBJ names itself as its library (found
// by fuzz_mesh after 720,240 executions: `mtllib m.obj` then `map_Kn...`).
TEST(HostileInput, MaterialLibraryStatementBeforeNewmtlIsRefused) {
    TempDir dir;
    dir.write("a.obj", std::string("mtllib a.mtl\n") + kTriangleObj);
    dir.write("a.mtl", "# a comment\n\nmap_Kd t.png\nnewmtl m\nKd 1 1 1\n");
    expect_mesh_refused(dir, "a.obj", "material library a.mtl line 3: 'map_Kd' before the first newmtl");
    dir.write("self.obj", "mtllib self.obj\nmap_Kn x\n");
    expect_mesh_refused(dir, "self.obj", "material library self.obj line 1: 'mtllib'");
    // Its default library, the OBJ's name with .mtl, is checked too.
    dir.write("b.obj", kTriangleObj);
    dir.write("b.mtl", "map_Ks t\n");
    expect_mesh_refused(dir, "b.obj", "material library b.mtl line 1: 'map_Ks'");
}
