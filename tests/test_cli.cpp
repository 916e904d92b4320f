// The command line, run as a user would: exit codes, messages, and what gets written.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <fstream>
#include <sstream>

#include "cli_run.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/image/image.h"

using namespace wavetrace;

namespace {

CliResult run(const TempDir& dir, const std::string& args) {
    return run_cli(dir, args);
}

std::string scene(const char* name) {
    return "'" + scene_path(name).string() + "'";
}

}  // namespace

TEST(Cli, RendersNormalAovOfTheDragon) {
    TempDir dir;
    auto out = dir.path() / "n.png";
    CliResult r = run(dir, "render " + scene("dragon") +
                               " --aov normal --width 64 --height 48 -o '" + out.string() + "'");
    EXPECT_EQ(r.code, 0) << r.err;
    ImageData img = read_image(out);
    EXPECT_EQ(img.width, 64);
    EXPECT_EQ(img.height, 48);
    EXPECT_NE(r.out.find("n.png"), std::string::npos);
}

TEST(Cli, InfoDescribesTheScene) {
    TempDir dir;
    CliResult r = run(dir, "info " + scene("everything"));
    EXPECT_EQ(r.code, 0) << r.err;
    for (const char* field : {"primitives   3408", "1007 spheres", "lights       1", "bounds",
                              "bvh", "SAH cost", "8-wide nodes", "simd         ", "memory"})
        EXPECT_NE(r.out.find(field), std::string::npos) << field << "\n" << r.out;
}

TEST(Cli, MalformedSceneExitsTwoNamingThePlaceAndWritesNothing) {
    TempDir dir;
    auto bad = dir.write("bad.json", R"({"camera": {"look_from": [0,0,-5], "look_at": [0,0,0]},
        "materials": {"w": {"type": "lambertian", "albedo": 0.5}},
        "objects": [{"type": "sphere", "center": [0,0,0], "radius": -1, "material": "w"}]})");
    auto out = dir.path() / "x.png";
    CliResult r = run(dir, "render '" + bad.string() + "' --aov albedo -o '" + out.string() + "'");
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find(bad.string() + ": /objects/0/radius: expected a positive number, got -1"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, BadOptionsExitTwoAndWriteNothing) {
    TempDir dir;
    auto out = dir.path() / "x.png";
    std::string o = " -o '" + out.string() + "'";
    EXPECT_EQ(run(dir, "render " + scene("cornell") + " --aov albedo --width 100000" + o).code, 2);
    CliResult huge =
        run(dir, "render " + scene("cornell") + " --aov albedo --width 30000 --height 30000" + o);
    EXPECT_EQ(huge.code, 2);
    EXPECT_NE(huge.err.find("exceeds the limit"), std::string::npos) << huge.err;
    EXPECT_EQ(run(dir, "render " + scene("cornell") + " --aov albedo --spp 0x" + o).code, 2);
    EXPECT_EQ(run(dir, "render " + scene("cornell") + " --aov bogus" + o).code, 2);
    EXPECT_EQ(run(dir, "render " + scene("cornell") + " --frobnicate" + o).code, 2);
    EXPECT_EQ(run(dir, "render " + scene("cornell") + " --strategy best" + o).code, 2);
    EXPECT_EQ(run(dir, "render " + scene("cornell") + " --max-depth 0x" + o).code, 2);
    EXPECT_EQ(run(dir, "render " + scene("cornell") + " --max-depth 5000" + o).code, 2);
    CliResult missing =
        run(dir, "render '" + (dir.path() / "none.json").string() + "' --aov albedo" + o);
    EXPECT_EQ(missing.code, 2);
    EXPECT_NE(missing.err.find("none.json: cannot open scene file"), std::string::npos)
        << missing.err;
    CliResult ext = run(dir, "render " + scene("cornell") + " --aov albedo -o '" +
                                 (dir.path() / "x.gif").string() + "'");
    EXPECT_EQ(ext.code, 2);
    EXPECT_NE(ext.err.find("unsupported output format"), std::string::npos) << ext.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_EQ(run(dir, "info '" + (dir.path() / "none.json").string() + "'").code, 2);
}

// A numeric option that is given must be valid: 0 or a negative value is not "the scene's".
TEST(Cli, ZeroOrNegativeCountsAreErrorsNotDefaults) {
    TempDir dir;
    auto out = dir.path() / "x.png";
    std::string o = " -o '" + out.string() + "'";
    for (const char* option : {"--spp 0", "--spp -4", "--width 0", "--height -1", "--max-depth 0",
                               "--wave-size 0", "--wave-size -1"}) {
        CliResult r = run(dir, "render " + scene("cornell") + " " + option + o);
        EXPECT_EQ(r.code, 2) << option;
        std::string name = std::string(option).substr(0, std::string(option).find(' '));
        EXPECT_NE(r.err.find(name + ": expected 1.."), std::string::npos) << option << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(Cli, VersionNamesTheBuildAndItsLibraries) {
    TempDir dir;
    CliResult r = run(dir, "--version");
    EXPECT_EQ(r.code, 0) << r.err;
    for (const char* field : {"wavetrace 0.", "build)", "SIMD:", "oneTBB:      20",
                              "OpenImageIO: 2.", "Assimp:      5.", "Embree:      3."})
        EXPECT_NE(r.out.find(field), std::string::npos) << field << "\n" << r.out;
}

TEST(Cli, ColorRenderRecordsItsSettingsInTheExr) {
    TempDir dir;
    auto out = dir.path() / "c.exr";
    CliResult r =
        run(dir, "render " + scene("cornell-smoke") +
                     " --strategy nee --mis-heuristic balance --spp 3 --seed 9 --max-depth 7"
                     " --width 20 --height 10 -o '" +
                     out.string() + "'");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("wavefront nee 20x10 3 spp"), std::string::npos)
        << r.err;  // the default engine
    EXPECT_NE(r.err.find("Mpaths/s"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("0 invalid samples"), std::string::npos) << r.err;
    auto in = OIIO::ImageInput::open(out.string());
    ASSERT_TRUE(in);
    const OIIO::ImageSpec& spec = in->spec();
    EXPECT_EQ(spec.get_string_attribute("wavetrace:engine"), "wavefront");
    EXPECT_EQ(spec.get_string_attribute("wavetrace:strategy"), "nee");
    EXPECT_EQ(spec.get_string_attribute("wavetrace:mis_heuristic"), "balance");
    EXPECT_EQ(spec.get_string_attribute("wavetrace:spp"), "3");
    EXPECT_EQ(spec.get_string_attribute("wavetrace:seed"), "9");
    EXPECT_EQ(spec.get_string_attribute("wavetrace:max_depth"), "7");
    EXPECT_NE(spec.get_string_attribute("wavetrace:scene").find("cornell-smoke.json"),
              std::string::npos);
    EXPECT_FALSE(spec.get_string_attribute("wavetrace:render_seconds").empty());
}

TEST(Cli, OutputDoesNotDependOnThreadCountOrSortingByMaterial) {
    TempDir dir;
    auto a = dir.path() / "a.exr", b = dir.path() / "b.exr";
    std::string common = "render " + scene("everything") + " --spp 3 --width 48 --height 48";
    ASSERT_EQ(run(dir, common + " --threads 1 -o '" + a.string() + "'").code, 0);
    ASSERT_EQ(run(dir, common + " --threads 2 --sort-by-material -o '" + b.string() + "'").code, 0);
    ImageData ia = read_image(a), ib = read_image(b);
    ASSERT_EQ(ia.texels.size(), ib.texels.size());
    for (size_t i = 0; i < ia.texels.size(); ++i) ASSERT_EQ(ia.texels[i], ib.texels[i]) << i;
}

// The wavefront's memory does not grow with the sample count: a 3840 x 2160 render at 4 spp
// peaks within 10% of the same render at 1 spp (the film, the same in both, dominates; the
// queues are sized by the wave, not by the image or the samples). Measured by each process's
// getrusage peak, as the CLI reports it. The scene is the Cornell box with one segment per
// path, to keep 33 M paths affordable.
TEST(Cli, WavefrontMemoryDoesNotGrowWithSamples) {
    TempDir dir;
    auto peak = [&](int spp) {
        CliResult r =
            run(dir, "render " + scene("cornell") +
                         " --engine wavefront --max-depth 1 --width 3840"
                         " --height 2160 --spp " +
                         std::to_string(spp) + " -o '" + (dir.path() / "big.pfm").string() + "'");
        EXPECT_EQ(r.code, 0) << r.err;
        auto at = r.err.find("peak memory ");
        EXPECT_NE(at, std::string::npos) << r.err;
        return at == std::string::npos ? 0.0 : std::stod(r.err.substr(at + 12));
    };
    // A buffer per sample would show at 4 spp as three more images' worth (~100 MiB each).
    double one = peak(1), four = peak(4);
    std::printf("peak memory 3840x2160: 1 spp %.1f MiB, 4 spp %.1f MiB\n", one, four);
    EXPECT_GT(one, 0.0);
    EXPECT_LE(four, 1.10 * one);
}

// --simd runs every kernel on the named target: each target this CPU runs gives the same
// image, bit for bit, and records itself in the header; an unknown one is refused.
TEST(Cli, EverySimdTargetRendersTheSameImage) {
    TempDir dir;
    const std::string common = "render " + scene("everything") + " --spp 2 --width 40 --height 30";
    ASSERT_EQ(run(dir, common + " -o '" + (dir.path() / "best.exr").string() + "'").code, 0);
    const ImageData best = read_image(dir.path() / "best.exr");
    for (const std::string& target : simd_targets()) {
        const auto out = dir.path() / (target + ".exr");
        CliResult r = run(dir, common + " --simd " + target + " -o '" + out.string() + "'");
        ASSERT_EQ(r.code, 0) << target << r.err;
        EXPECT_TRUE(read_image(out).texels == best.texels) << target;
        auto in = OIIO::ImageInput::open(out.string());
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().get_string_attribute("wavetrace:simd"), target);
    }
    CliResult bad = run(dir, common + " --simd NEON -o '" + (dir.path() / "x.exr").string() + "'");
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("--simd NEON: not a target this CPU runs"), std::string::npos) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "x.exr"));
}
