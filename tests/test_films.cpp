// Film files: an interrupted render resumed from its film equals the uninterrupted render bit
// for bit (both engines); sample ranges rendered apart and merged in any order equal the single
// render within 1e-6 relative; mismatched, overlapping and damaged films are refused.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "cli_run.h"
#include "wavetrace/film/film_file.h"
#include "wavetrace/image/image.h"

using namespace wavetrace;

namespace {

std::string bytes_of(const std::filesystem::path& p) {
    std::stringstream s;
    s << std::ifstream(p, std::ios::binary).rdbuf();
    return s.str();
}

std::string q(const std::filesystem::path& p) {
    return "'" + p.string() + "'";
}

const std::string kRender =
    "render " + scene_path("cornell-smoke").string() + " --width 40 --height 30 --seed 3 ";

// Samples per pixel of kRender that last a few seconds on one thread (kInterrupted), also under
// AddressSanitizer (whose renders are about 20 times slower): a signal sent after the first
// checkpoint comes well before the end, on a machine of any size. The render that is
// interrupted runs on one thread, the uninterrupted one and the resumption on all of them:
// the film does not depend on the thread count.
constexpr int kLongRenderSpp = kUnderAddressSanitizer ? 200 : 1500;
const std::string kInterrupted = "--threads 1 ";

// Shell commands that wait until the render in the background has written its first
// checkpoint, dir/part.film (at most 60 s): the render has then started, its signal handlers
// are installed and a pass is done, however slow the start-up (a sanitized build on a slow
// machine takes over a second to load and build the BVH).
std::string after_first_checkpoint(const TempDir& dir) {
    return "for i in $(seq 1200); do [ -e " + q(dir.path() / "part.film") +
           " ] && break; sleep 0.05; done; ";
}

}  // namespace

// A render interrupted by SIGINT (its film written at the end, its checkpoints refreshed
// during it) and resumed to the requested spp: the same film file, byte for byte, as the render
// that was never stopped — and so the same image. Both engines, and the Sobol samplers.
TEST(Films, InterruptedAndResumedEqualsUninterruptedBitForBit) {
    for (const char* engine :
         {"wavefront", "megakernel", "wavefront --sampler sobol", "megakernel --sampler zsobol"}) {
        TempDir dir;
        const std::string common = kRender + "--engine " + engine;
        const int spp = kLongRenderSpp;
        ASSERT_EQ(
            run_cli(dir, common + " --spp " + std::to_string(spp) + " -o " +
                             q(dir.path() / "full.exr") + " --film " + q(dir.path() / "full.film"))
                .code,
            0);
        // Interrupt after the first checkpoint, checkpointing every 0.1 s meanwhile.
        const std::string script =
            "'" + cli_path().string() + "' " + common + " --spp " + std::to_string(spp) + " " +
            kInterrupted + "--checkpoint-every 0.1 -o " + q(dir.path() / "part.exr") + " --film " +
            q(dir.path() / "part.film") + " 2> " + q(dir.path() / "err") + " > /dev/null & p=$!; " +
            after_first_checkpoint(dir) + "kill -INT $p; wait $p";
        const int status = std::system(script.c_str());
        ASSERT_EQ(WEXITSTATUS(status), 130) << engine << bytes_of(dir.path() / "err");
        auto [part, info] = load_film(dir.path() / "part.film");
        ASSERT_EQ(info.ranges.size(), 1u);
        EXPECT_EQ(info.ranges[0].first, 0u);
        EXPECT_GT(info.samples(), 0u) << engine;
        EXPECT_LT(info.samples(), uint32_t(spp)) << engine << ": interrupt sooner";
        CliResult resumed =
            run_cli(dir, common + " --spp " + std::to_string(spp) + " --resume " +
                             q(dir.path() / "part.film") + " -o " + q(dir.path() / "resumed.exr"));
        ASSERT_EQ(resumed.code, 0) << resumed.err;
        EXPECT_NE(resumed.err.find(" resumed, "), std::string::npos) << resumed.err;
        EXPECT_TRUE(bytes_of(dir.path() / "part.film") == bytes_of(dir.path() / "full.film"))
            << engine << ": the resumed film differs from the uninterrupted one";
        ImageData a = read_image(dir.path() / "full.exr"),
                  b = read_image(dir.path() / "resumed.exr");
        EXPECT_TRUE(a.texels == b.texels) << engine;
    }
}

// Two- and four-way splits of [0, 24), rendered apart and merged in shuffled order: the
// single render within 1e-6 relative per pixel (sums of doubles, associated differently), and
// the same bits whatever the order; for each sampler.
TEST(Films, SplitsMergedInAnyOrderEqualTheSingleRender) {
    for (const std::string sampler : {"independent", "sobol", "zsobol"}) {
    SCOPED_TRACE(sampler);
    // zsobol's parts state the whole render's count, which its layout depends on.
    const std::string render =
        kRender + "--sampler " + sampler + (sampler == "zsobol" ? " --sampler-spp 24 " : " ");
    TempDir dir;
    ASSERT_EQ(run_cli(dir, render + "--spp 24 -o " + q(dir.path() / "full.exr")).code, 0);
    const ImageData full = read_image(dir.path() / "full.exr");
    std::mt19937 rng(7);
    for (int ways : {2, 4}) {
        std::vector<std::string> parts;
        for (int k = 0; k < ways; ++k) {
            const int n = 24 / ways;
            const auto film =
                dir.path() / ("p" + std::to_string(ways) + "_" + std::to_string(k) + ".film");
            ASSERT_EQ(run_cli(dir, render + "--spp " + std::to_string(n) + " --sample-offset " +
                                       std::to_string(k * n) + " -o " + q(dir.path() / "part.exr") +
                                       " --film " + q(film))
                          .code,
                      0);
            parts.push_back(q(film));
        }
        std::string previous;
        for (int shuffle = 0; shuffle < 2; ++shuffle) {
            std::shuffle(parts.begin(), parts.end(), rng);
            std::string args;
            for (const std::string& p : parts) args += " " + p;
            CliResult m = run_cli(dir, "merge" + args + " -o " + q(dir.path() / "merged.exr") +
                                           " --film " + q(dir.path() / "merged.film"));
            ASSERT_EQ(m.code, 0) << m.err;
            EXPECT_NE(m.err.find("samples [0, 24) (24 spp)"), std::string::npos) << m.err;
            const ImageData merged = read_image(dir.path() / "merged.exr");
            double worst = 0;
            for (size_t i = 0; i < full.texels.size(); ++i)
                for (int c = 0; c < 3; ++c) {
                    const double f = full.texels[i][c], g = merged.texels[i][c];
                    worst = std::max(worst, std::fabs(f - g) / std::max(std::fabs(f), 1e-30));
                }
            EXPECT_LE(worst, 1e-6) << ways << "-way split";
            const std::string bits = bytes_of(dir.path() / "merged.film");
            if (!previous.empty()) {
                EXPECT_TRUE(bits == previous) << "order changed the bits";
            }
            previous = bits;
        }
    }
    }
}

TEST(Films, MismatchedOverlappingAndDamagedFilmsAreRefused) {
    TempDir dir;
    auto film = [&](const char* name) { return dir.path() / name; };
    ASSERT_EQ(
        run_cli(dir, kRender + "--spp 2 -o " + q(film("a.exr")) + " --film " + q(film("a.film")))
            .code,
        0);
    ASSERT_EQ(run_cli(dir, kRender + "--spp 2 --sample-offset 1 -o " + q(film("b.exr")) +
                               " --film " + q(film("b.film")))
                  .code,
              0);
    // Another seed: another render.
    CliResult other = run_cli(dir, "render " + scene_path("cornell-smoke").string() +
                                       " --width 40 --height 30 --seed 4 --spp 4 --resume " +
                                       q(film("a.film")) + " -o " + q(film("x.exr")));
    EXPECT_EQ(other.code, 2);
    EXPECT_NE(other.err.find("the film of another render (seed: 3 vs 4)"), std::string::npos)
        << other.err;
    EXPECT_FALSE(std::filesystem::exists(film("x.exr")));
    // Another sampler: another render.
    CliResult sobol = run_cli(dir, kRender + "--spp 4 --sampler independent --resume " +
                                       q(film("a.film")) + " -o " + q(film("x.exr")));
    EXPECT_EQ(sobol.code, 2);
    EXPECT_NE(sobol.err.find("the film of another render (sampler: sobol vs (none))"),
              std::string::npos)
        << sobol.err;
    EXPECT_FALSE(std::filesystem::exists(film("x.exr")));
    // zsobol laid out for another count: another render (its parts state the whole count).
    ASSERT_EQ(run_cli(dir, kRender + "--spp 2 --sampler zsobol -o " + q(film("z.exr")) +
                               " --film " + q(film("z.film")))
                  .code,
              0);
    CliResult layout = run_cli(dir, kRender + "--spp 8 --sampler zsobol --resume " +
                                        q(film("z.film")) + " -o " + q(film("x.exr")));
    EXPECT_EQ(layout.code, 2);
    EXPECT_NE(layout.err.find("the film of another render (zsobol_spp: 2 vs 8)"),
              std::string::npos)
        << layout.err;
    EXPECT_EQ(run_cli(dir, kRender + "--spp 8 --sampler zsobol --sampler-spp 2 --resume " +
                               q(film("z.film")) + " -o " + q(film("x.exr")))
                  .code,
              0);
    std::filesystem::remove(film("x.exr"));
    // Overlapping parts: [0, 2) and [1, 3).
    CliResult overlap = run_cli(
        dir, "merge " + q(film("a.film")) + " " + q(film("b.film")) + " -o " + q(film("m.exr")));
    EXPECT_EQ(overlap.code, 2);
    EXPECT_NE(overlap.err.find("sample ranges overlap: [0, 2) and [1, 3)"), std::string::npos)
        << overlap.err;
    // Resuming a film that does not start at the offset asked for.
    CliResult offset =
        run_cli(dir, kRender + "--spp 4 --resume " + q(film("b.film")) + " -o " + q(film("x.exr")));
    EXPECT_EQ(offset.code, 2);
    EXPECT_NE(offset.err.find("holds samples [1, 3), not a range from --sample-offset 0"),
              std::string::npos)
        << offset.err;
    // A damaged film (one byte flipped in its sums) and a truncated one.
    std::string bytes = bytes_of(film("a.film"));
    bytes[bytes.size() / 2] ^= 0x40;
    std::ofstream(film("damaged.film"), std::ios::binary) << bytes;
    std::ofstream(film("short.film"), std::ios::binary) << bytes.substr(0, bytes.size() / 3);
    for (const char* name : {"damaged.film", "short.film"}) {
        CliResult r = run_cli(dir, "merge " + q(film(name)) + " -o " + q(film("m.exr")));
        EXPECT_EQ(r.code, 2) << name;
        EXPECT_NE(r.err.find(std::string(name) + ": not a film file wavetrace can read"),
                  std::string::npos)
            << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(film("m.exr")));
    // Options that need a film.
    EXPECT_EQ(run_cli(dir, kRender + "--spp 2 --checkpoint-every 1 -o " + q(film("x.exr"))).code,
              2);
}

// A render killed outright (SIGKILL: no chance to write anything at the end) leaves the film of
// its last checkpoint, and resuming from it still gives the uninterrupted film.
TEST(Films, CheckpointSurvivesAKillAndResumesBitForBit) {
    TempDir dir;
    const std::string common = kRender + "--spp " + std::to_string(kLongRenderSpp);
    ASSERT_EQ(run_cli(dir, common + " -o " + q(dir.path() / "full.exr") + " --film " +
                               q(dir.path() / "full.film"))
                  .code,
              0);
    const std::string script = "'" + cli_path().string() + "' " + common + " " + kInterrupted +
                               "--checkpoint-every 0.1 -o " + q(dir.path() / "part.exr") +
                               " --film " + q(dir.path() / "part.film") +
                               " 2> /dev/null > /dev/null & p=$!; " + after_first_checkpoint(dir) +
                               "kill -KILL $p; wait $p";
    std::system(script.c_str());
    EXPECT_FALSE(std::filesystem::exists(dir.path() / "part.exr"));
    auto [film, info] = load_film(dir.path() / "part.film");
    EXPECT_GT(info.samples(), 0u);
    EXPECT_LT(info.samples(), uint32_t(kLongRenderSpp));
    ASSERT_EQ(run_cli(dir, common + " --resume " + q(dir.path() / "part.film") + " -o " +
                               q(dir.path() / "resumed.exr"))
                  .code,
              0);
    EXPECT_TRUE(bytes_of(dir.path() / "part.film") == bytes_of(dir.path() / "full.film"));
}
