// Renders in passes: a stop between passes leaves every pixel with the same sample count and
// the image of those samples, bit for bit; sample ranges add up to the whole; and the CLI
// turns SIGINT, SIGTERM and --time-limit into the image of the completed passes.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "render_film.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "wavetrace/accel/bvh.h"
#include "wavetrace/engines/render.h"
#include "wavetrace/loaders/load_scene.h"
#include "wavetrace/scene/scene.h"

using namespace wavetrace;

namespace {

RenderRequest small_config(int spp) {
    RenderRequest c;
    c.width = 37;  // not a multiple of the wave size below
    c.height = 23;
    c.spp = spp;
    c.seed = 3;
    return c;
}

void expect_same_film(const Film& a, const Film& b, int samples) {
    Image ia = a.mean(), ib = b.mean();
    ASSERT_EQ(ia.pixels.size(), ib.pixels.size());
    for (size_t i = 0; i < ia.pixels.size(); ++i) {
        ASSERT_EQ(a.samples(int(i)), uint32_t(samples));
        ASSERT_EQ(b.samples(int(i)), uint32_t(samples));
        ASSERT_EQ(0, std::memcmp(&ia.pixels[i], &ib.pixels[i], sizeof(Color))) << "pixel " << i;
    }
}

}  // namespace

// Stops the render at its `stop_at`-th check; checks that it is asked before the first pass
// and after each.
class StopAt : public RenderObserver {
  public:
    explicit StopAt(int stop_at) : stop_at_(stop_at) {}
    bool on_pass(int done, int, const Film&) override {
        EXPECT_EQ(done, calls_);  // a check before the first pass and one after it
        return ++calls_ < stop_at_;
    }

  private:
    int stop_at_, calls_ = 0;
};

TEST(Passes, StoppingBetweenPassesGivesTheImageOfTheSamplesDone) {
    Scene scene = load_scene(scene_path("cornell-smoke"));
    Bvh bvh = Bvh::build(scene);
    // Both engines' first pass is one sample (the later ones last about half a second): stop
    // at the second check.
    for (Engine engine : {Engine::Wavefront, Engine::Megakernel}) {
        RenderRequest request = small_config(10);
        request.engine = engine;
        request.wavefront.wave_size = 300;
        Film film(request.width, request.height);
        StopAt stop(2);
        RenderStats stats = render(scene, bvh, request, film, &stop);
        EXPECT_EQ(stats.spp_done, 1);
        RenderRequest one = request;
        one.spp = 1;
        Film reference(one.width, one.height);
        render(scene, bvh, one, reference);
        expect_same_film(film, reference, 1);
    }
}

TEST(Passes, SampleRangesAddUpToTheWholeRender) {
    Scene scene = load_scene(scene_path("cornell"));
    Bvh bvh = Bvh::build(scene);
    for (Engine engine : {Engine::Wavefront, Engine::Megakernel})
    for (SamplerKind kind : {SamplerKind::Independent, SamplerKind::Sobol, SamplerKind::ZSobol}) {
        RenderRequest first = small_config(3), second = small_config(4), all = small_config(7);
        second.first_sample = 3;
        for (RenderRequest* r : {&first, &second, &all}) {
            r->engine = engine;
            r->sampler = kind;
            r->sampler_spp = 7;  // zsobol: each part laid out for the whole render
            r->wavefront.wave_size = 300;
        }
        Film parts(first.width, first.height), whole(first.width, first.height);
        render(scene, bvh, first, parts);
        render(scene, bvh, second, parts);
        render(scene, bvh, all, whole);
        expect_same_film(parts, whole, 7);
    }
}

namespace {

struct Stopped {
    int status;  // as from waitpid
    std::string err;
    bool guard_left = false;  // the guard's sleep outlived the render: a process left behind
};

// Starts a long render, sends `signals` (e.g. "INT") after `delay` seconds, 0.05 s apart,
// and waits for it.
Stopped render_and_signal(const TempDir& dir,
                          const std::string& args,
                          const std::string& delay,
                          const std::vector<std::string>& signals) {
    // Run by std::system's sh; a guard kills the render after 60 s, so that one that ignored
    // the signal fails the test instead of running on. Stopped, the guard stops its own sleep
    // too and waits for it: a sleep left running would hold ctest's pipe open until it ends.
    const std::string guard_pid = (dir.path() / "guard-pid").string();
    std::string script = "'" + cli_path().string() + "' render " + args + " 2> '" +
                         (dir.path() / "err").string() + "' > /dev/null & p=$!; " +
                         "(trap 'kill $s; wait $s; exit 0' TERM; sleep 60 & s=$!; echo $s > '" +
                         guard_pid + "'; wait $s; kill -9 $p) > /dev/null 2>&1 & guard=$!; " +
                         "sleep " + delay + ";";
    for (const std::string& s : signals) script += " kill -" + s + " $p; sleep 0.05;";
    script += " wait $p; status=$?; kill $guard 2> /dev/null; wait $guard; exit $status";
    int status = std::system(script.c_str());
    std::stringstream err;
    err << std::ifstream(dir.path() / "err").rdbuf();
    Stopped r{status, err.str()};
    pid_t sleeper = 0;
    std::ifstream(guard_pid) >> sleeper;
    r.guard_left = sleeper <= 0 || ::kill(sleeper, 0) == 0;
    std::filesystem::remove(guard_pid);
    return r;
}

int spp_in_header(const std::filesystem::path& exr) {
    auto in = OIIO::ImageInput::open(exr.string());
    if (!in) return -1;
    return std::stoi(in->spec().get_string_attribute("wavetrace:spp", "-1"));
}

}  // namespace

TEST(Passes, SigintWritesTheCompletedPassesAndExits130) {
    for (const char* engine : {"wavefront", "megakernel"}) {
        TempDir dir;
        auto out = dir.path() / "x.exr";
        Stopped r = render_and_signal(dir,
                                      "'" + scene_path("cornell").string() + "' --engine " +
                                          engine + " --width 128 --height 128 --spp 1000000 -o '" +
                                          out.string() + "'",
                                      "2", {"INT"});
        ASSERT_TRUE(WIFEXITED(r.status)) << engine << r.err;
        EXPECT_EQ(WEXITSTATUS(r.status), 130) << engine << r.err;
        EXPECT_FALSE(r.guard_left) << "no process outlives the test";
        EXPECT_NE(r.err.find("of 1000000 requested (interrupted)"), std::string::npos) << r.err;
        int spp = spp_in_header(out);
        EXPECT_GE(spp, 1) << engine;
        EXPECT_LT(spp, 1000000) << engine;
        size_t files = 0;
        for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path()))
            ++files;
        EXPECT_EQ(files, 2u) << "the image and the captured stderr, nothing else";
    }
}

// A SIGINT that arrives while a checkpoint is being written still stops the render at the
// next pass boundary with the image of the passes done: the temporary file's guard hands the
// signal to the CLI's handler instead of ending the process. Twenty signals at delays spread
// over a checkpoint interval of 50 ms, once the render is under way (before that a
// background job ignores SIGINT).
TEST(Passes, SigintDuringCheckpointsAlwaysLeavesAnImage) {
    for (int i = 0; i < 20; ++i) {
        TempDir dir;
        const auto out = dir.path() / "x.exr", film = dir.path() / "x.film";
        const std::string delay = std::to_string(1.5 + 0.0037 * i);  // once rendering
        Stopped r = render_and_signal(
            dir,
            "'" + scene_path("cornell").string() +
                "' --width 96 --height 96 --spp 1000000 --checkpoint-every 0.05 --film '" +
                film.string() + "' -o '" + out.string() + "'",
            delay, {"INT"});
        ASSERT_TRUE(WIFEXITED(r.status)) << "signal " << i << ": " << r.err;
        EXPECT_EQ(WEXITSTATUS(r.status), 130) << "signal " << i << ": " << r.err;
        EXPECT_GE(spp_in_header(out), 1) << "signal " << i;
        size_t files = 0;
        for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path()))
            ++files;
        EXPECT_EQ(files, 3u) << "signal " << i << ": the image, the film and the captured stderr";
    }
}

TEST(Passes, SigtermExits143AndSecondSigintAbortsAtOnce) {
    TempDir dir;
    auto out = dir.path() / "x.exr";
    std::string args = "'" + scene_path("cornell").string() +
                       "' --width 128 --height 128 --spp 1000000 -o '" + out.string() + "'";
    Stopped term = render_and_signal(dir, args, "2", {"TERM"});
    ASSERT_TRUE(WIFEXITED(term.status)) << term.err;
    EXPECT_EQ(WEXITSTATUS(term.status), 143) << term.err;
    EXPECT_GE(spp_in_header(out), 1);
    std::filesystem::remove(out);
    // Two Ctrl-C in a row: the second ends the process without waiting for the pass.
    Stopped twice = render_and_signal(
        dir, "'" + scene_path("dragon").string() + "' --spp 1000000 -o '" + out.string() + "'", "3",
        {"INT", "INT"});
    EXPECT_EQ(WEXITSTATUS(twice.status), 128 + SIGINT)
        << "bash reports death by SIGINT: " << twice.err;
    EXPECT_FALSE(term.guard_left || twice.guard_left) << "no process outlives the test";
    EXPECT_EQ(twice.err.find("requested (interrupted)"), std::string::npos) << twice.err;
}

TEST(Passes, TimeLimitRendersWholePassesThenWrites) {
    TempDir dir;
    auto out = dir.path() / "x.exr";
    int status =
        std::system(("'" + cli_path().string() + "' render '" + scene_path("cornell").string() +
                     "' --width 128 --height 128 --spp 1000000 --time-limit 1 -o '" + out.string() +
                     "' 2> '" + (dir.path() / "err").string() + "'")
                        .c_str());
    std::stringstream err;
    err << std::ifstream(dir.path() / "err").rdbuf();
    EXPECT_EQ(WEXITSTATUS(status), 0) << err.str();
    EXPECT_NE(err.str().find("of 1000000 requested (time limit reached)"), std::string::npos)
        << err.str();
    int spp = spp_in_header(out);
    EXPECT_GE(spp, 1);
    EXPECT_LT(spp, 1000000);
}

// In a terminal (a pseudo-terminal from util-linux's `script`), the progress line shows the
// samples done of the total and, with a time limit, the time left counting down; a SIGINT
// there still writes the image of the completed passes and exits 130.
TEST(Passes, ProgressLineInATerminalCountsSamplesAndTimeLeft) {
    TempDir dir;
    auto out = dir.path() / "x.exr";
    const std::string render = "'" + cli_path().string() + "' render '" +
                               scene_path("cornell").string() +
                               "' --width 128 --height 128 --spp 1000000 -o '" + out.string() + "'";
    auto in_terminal = [&](const std::string& cmd) {
        const std::string log = (dir.path() / "tty").string();
        int status =
            std::system(("script -qfec \"" + cmd + "\" '" + log + "' > /dev/null").c_str());
        std::stringstream s;
        s << std::ifstream(log).rdbuf();
        return std::pair{status, s.str()};
    };
    auto [status, tty] = in_terminal(render + " --time-limit 1.5");
    EXPECT_EQ(WEXITSTATUS(status), 0) << tty;
    EXPECT_NE(tty.find("/1000000 spp"), std::string::npos) << tty;
    EXPECT_NE(tty.find("time left"), std::string::npos) << tty;
    EXPECT_GE(spp_in_header(out), 1);
    std::filesystem::remove(out);
    // SIGINT, then SIGTERM, to the render inside the terminal: the image of the passes done,
    // its sample count in the header, exit 130 / 143, and no file but the image and the log.
    for (auto [sig, code] : {std::pair{"INT", 130}, std::pair{"TERM", 143}}) {
        std::filesystem::remove(out);
        auto [sig_status, sig_tty] =
            in_terminal(render + " & p=\\$!; sleep 1.5; kill -" + sig + " \\$p; wait \\$p");
        EXPECT_EQ(WEXITSTATUS(sig_status), code) << sig << sig_tty;
        EXPECT_NE(sig_tty.find("ETA"), std::string::npos) << sig_tty;
        const int spp = spp_in_header(out);
        EXPECT_GE(spp, 1) << sig;
        EXPECT_LT(spp, 1000000) << sig;
        std::vector<std::string> files;
        for (const auto& e : std::filesystem::directory_iterator(dir.path()))
            files.push_back(e.path().filename().string());
        std::sort(files.begin(), files.end());
        EXPECT_EQ(files, (std::vector<std::string>{"tty", "x.exr"})) << sig;
    }
}

namespace {
// Records where and what render() reports, and stops after `stop_at` samples.
class Recorder : public RenderObserver {
  public:
    explicit Recorder(int stop_at) : stop_at_(stop_at) {}
    bool on_pass(int done, int requested, const Film&) override {
        threads.push_back(std::this_thread::get_id());
        reports.push_back({done, requested});
        return done < stop_at_;
    }
    void on_progress(double fraction) override {
        std::lock_guard<std::mutex> lock(mutex);
        fractions.push_back(fraction);
    }
    std::vector<std::thread::id> threads;
    std::vector<std::pair<int, int>> reports;
    std::mutex mutex;
    std::vector<double> fractions;

  private:
    int stop_at_;
};
}  // namespace

// render(): either engine from one call; the observer's passes run on the caller's thread
// between passes, see the samples done, and stop the render by returning false; its progress
// fractions grow to 1.
TEST(Passes, RenderCallReportsOnTheCallersThreadAndCancels) {
    Scene scene = load_scene(scene_path("cornell"));
    Bvh bvh = Bvh::build(scene);
    for (Engine engine : {Engine::Wavefront, Engine::Megakernel}) {
        RenderRequest request = small_config(6);
        request.engine = engine;
        request.wavefront.wave_size = 300;
        Film film(request.width, request.height);
        Recorder all(1000);
        RenderStats stats = render(scene, bvh, request, film, &all);
        EXPECT_EQ(stats.spp_done, 6);
        ASSERT_FALSE(all.reports.empty());
        EXPECT_EQ(all.reports.front(), std::make_pair(0, 6));
        EXPECT_EQ(all.reports.back(), std::make_pair(6, 6));
        for (std::thread::id id : all.threads) EXPECT_EQ(id, std::this_thread::get_id());
        ASSERT_FALSE(all.fractions.empty());
        std::sort(all.fractions.begin(), all.fractions.end());
        EXPECT_GT(all.fractions.front(), 0.0);
        EXPECT_DOUBLE_EQ(all.fractions.back(), 1.0);
        // The same film as one pass without an observer.
        Film direct(request.width, request.height);
        render(scene, bvh, request, direct);
        expect_same_film(film, direct, 6);
        // The first pass is one sample: stop after it.
        Film stopped(request.width, request.height);
        Recorder one(1);
        EXPECT_EQ(render(scene, bvh, request, stopped, &one).spp_done, 1);
        RenderRequest first = request;
        first.spp = 1;
        Film reference(first.width, first.height);
        render(scene, bvh, first, reference);
        expect_same_film(stopped, reference, 1);
    }
}
