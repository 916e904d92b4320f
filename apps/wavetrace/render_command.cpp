#include <fmt/core.h>
#include <sys/resource.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <mutex>
#include <optional>

#include "commands.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::cli {
namespace fs = std::filesystem;

void add_render_command(CLI::App& app, RenderOptions& o) {
    CLI::App* cmd = app.add_subcommand("render", "render a scene file to an image");
    cmd->add_option("scene", o.scene, "scene file (JSON, Mitsuba 3 XML, or glTF: .gltf, .glb)")
        ->required();
    cmd->add_option("-D,--define", o.defines,
                    "Mitsuba scenes: NAME=VALUE for a $NAME parameter (overrides <default>)");
    cmd->add_option("--asset-root", o.asset_root,
                    "every file the scene reads (meshes, textures, includes, and what meshes name) "
                    "must lie inside this folder, symbolic links resolved");
    cmd->add_option("-o,--output", o.output,
                    "output image: .png/.jpg (8-bit sRGB) or .exr/.hdr/.pfm (linear float); "
                    "default: <scene>.png");
    cmd->add_option("--width", o.width, "image width in pixels (default: the scene's)");
    cmd->add_option("--height", o.height, "image height in pixels (default: the scene's)");
    cmd->add_option("--spp", o.spp, "samples per pixel (default: the scene's)");
    cmd->add_option("--seed", o.seed, "random seed")->capture_default_str();
    cmd->add_option("--threads", o.threads, "worker threads (default: all)");
    cmd->add_option("--aov", o.aov, "what to render: color (light transport) or a primary-ray AOV")
        ->check(CLI::IsMember({"color", "albedo", "normal", "depth"}))
        ->capture_default_str();
    cmd->add_option("--exposure", o.exposure, "exposure in stops for .png/.jpg output")
        ->capture_default_str();
    cmd->add_option("--engine", o.engine, "light-transport engine")
        ->check(CLI::IsMember({"wavefront", "megakernel"}))
        ->capture_default_str();
    cmd->add_option("--camera", o.camera,
                    "glTF scenes: the camera to render through, by name (default: the first)");
    cmd->add_option("--strategy", o.strategy, "estimator of the rendering equation")
        ->check(CLI::IsMember({"bsdf", "light", "mixture", "nee", "mis"}))
        ->capture_default_str();
    cmd->add_option("--sampler", o.sampler,
                    "where the random numbers come from: independent (a hash of each "
                    "coordinate), sobol (Owen-scrambled Sobol points per pixel) or zsobol (one "
                    "Owen-scrambled Sobol sequence over the pixels in a shuffled Morton order: "
                    "blue-noise error); default: the scene's")
        ->check(CLI::IsMember({"independent", "sobol", "zsobol"}));
    cmd->add_option("--sampler-spp", o.sampler_spp,
                    "zsobol: the samples per pixel its sequence is laid out for (default: "
                    "--sample-offset + --spp); every part of a split or resumed render states "
                    "the same");
    cmd->add_option("--simd", o.simd,
                    "run every kernel on this SIMD target (Highway's name, e.g. AVX2; default: "
                    "the best this CPU runs), to measure what other CPUs get");
    cmd->add_option("--mis-heuristic", o.heuristic,
                    "MIS weighting heuristic (an environment map sampled with MIS compensation "
                    "is weighed by the balance heuristic either way)")
        ->check(CLI::IsMember({"balance", "power"}))
        ->capture_default_str();
    cmd->add_option("--max-depth", o.max_depth,
                    "most ray segments per path (default: the scene's)");
    cmd->add_option("--time-limit", o.time_limit,
                    "render whole passes (one sample per pixel) until SECONDS have passed, then "
                    "write the image of the passes done");
    cmd->add_option("--wave-size", o.wave_size,
                    "wavefront: paths a thread carries at once (default 4096; a small image's "
                    "waves carry several samples of each pixel)");
    cmd->add_option("--schedule", o.schedule,
                    "wavefront: how threads share the kernels: resident (each thread carries its "
                    "own wave through every kernel) or stage (each kernel a parallel loop over one "
                    "wave); the image is the same")
        ->check(CLI::IsMember({"resident", "stage"}))
        ->capture_default_str();
    cmd->add_flag("--sort-by-material", o.sort_by_material,
                  "wavefront: reorder each bounce's paths by material kind before shading (off by "
                  "default: it costs more than it gains; the image is the same)");
    cmd->add_option("--film", o.film,
                    "also write the film (per-pixel sums, docs/film-format.md) at the end: to "
                    "resume or merge the render");
    cmd->add_option("--checkpoint-every", o.checkpoint_every,
                    "refresh the film file every SECONDS during the render (needs --film or "
                    "--resume)");
    cmd->add_option("--resume", o.resume,
                    "continue the render in this film file up to --spp samples (it is updated "
                    "unless --film names another file)");
    cmd->add_option("--sample-offset", o.sample_offset,
                    "render samples [K, K + spp) of each pixel's sequence (default 0): parts of "
                    "one render for `wavetrace merge`");
    cmd->add_option("--variance", o.variance,
                    "also write the variance of each pixel's mean (per channel; .exr, .hdr or "
                    ".pfm): for `wavetrace compare`");
}

namespace {

// The first SIGINT or SIGTERM asks the render to stop at the next pass boundary (the image of
// the completed passes is then written, and the process exits 130 / 143); a second SIGINT
// aborts at once.
std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free, "read and written in a signal handler");

extern "C" void on_stop_signal(int sig) {
    if (sig == SIGINT && g_stop_signal.load() != 0) {
        std::signal(SIGINT, SIG_DFL);
        std::raise(SIGINT);
        return;
    }
    g_stop_signal.store(sig);
}

// Memory ran out at a step that says which (the film's own shortage is reported below).
struct OutOfMemory : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// The process's peak resident set so far (getrusage reports KiB on Linux).
double peak_rss_mib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024.0;
}

void map_aov_to_display(Aov aov, Image& image) {
    if (aov == Aov::Normal) {
        for (Color& c : image.pixels)
            if (c.x != 0 || c.y != 0 || c.z != 0) c = 0.5f * (c + Color(1.0f));
    } else if (aov == Aov::Depth) {
        float far = 0;
        for (const Color& c : image.pixels)
            if (std::isfinite(c.x)) far = std::max(far, c.x);
        for (Color& c : image.pixels) c = std::isfinite(c.x) && far > 0 ? c / far : Color(1.0f);
    }
}

// Watches a colour render: a progress line on stderr, only when stderr is a terminal (samples
// per pixel done of the total, resumed ones included, percent, elapsed, ETA or, with a time
// limit, the time left counting down, Mpaths/s); a checkpoint of the film between passes
// every --checkpoint-every seconds; and the stop at a signal (the time limit is the request's).
class RenderWatch : public RenderObserver {
  public:
    // `checkpoint(film, samples_done)` writes the film file; `time_limit` and `every` are in
    // seconds.
    RenderWatch(const RenderRequest& request,
                int already,
                std::optional<double> time_limit,
                std::optional<double> every,
                std::function<void(const Film&, int)> checkpoint)
        : enabled_(::isatty(2)),
          paths_(double(request.width) * request.height * request.spp),
          spp_(request.spp),
          already_(already),
          time_limit_(time_limit),
          every_(every),
          checkpoint_(std::move(checkpoint)),
          start_(std::chrono::steady_clock::now()),
          last_checkpoint_(start_) {}

    // Between passes nothing is added to the film: a consistent snapshot.
    bool on_pass(int done, int requested, const Film& film) override {
        const auto now = std::chrono::steady_clock::now();
        if (done == requested) return true;  // finished: the caller writes the film
        if (every_ && done > 0 &&
            std::chrono::duration<double>(now - last_checkpoint_).count() >= *every_) {
            checkpoint_(film, done);
            last_checkpoint_ = now;
        }
        return g_stop_signal.load() == 0;  // the time limit is the request's
    }

    void on_progress(double fraction) override {
        if (!enabled_) return;
        auto now = std::chrono::steady_clock::now();
        std::lock_guard<std::mutex> lock(mutex_);
        if (now - last_line_ < std::chrono::milliseconds(200) && fraction < 1.0) return;
        last_line_ = now;
        const double elapsed = std::chrono::duration<double>(now - start_).count();
        const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
        const int done = already_ + static_cast<int>(fraction * spp_);
        const std::string left =
            time_limit_ ? fmt::format("time left {:6.1f} s", std::max(0.0, *time_limit_ - elapsed))
                        : fmt::format("ETA {:6.1f} s", eta);
        std::fprintf(stderr, "\r%d/%d spp  %5.1f%%  elapsed %6.1f s  %s  %6.2f Mpaths/s   ", done,
                     already_ + spp_, 100 * fraction, elapsed, left.c_str(),
                     paths_ * fraction / std::max(elapsed, 1e-9) * 1e-6);
    }

    void finish() {
        if (enabled_) std::fprintf(stderr, "\r%90s\r", "");
    }

  private:
    bool enabled_;
    double paths_;
    int spp_, already_;
    std::optional<double> time_limit_, every_;
    std::function<void(const Film&, int)> checkpoint_;
    std::chrono::steady_clock::time_point start_, last_checkpoint_, last_line_{};
    std::mutex mutex_;
};

// Range checks shared by all numeric options: each failure names the option. An option that
// is given must be valid: 0 is an error, not a request for the scene's value.
std::optional<std::string> check_options(const RenderOptions& o, const RenderSettings& r) {
    auto out_of_range = [](const char* name, const auto& value, long long lo,
                           long long hi) -> std::optional<std::string> {
        if (value && (*value < lo || *value > hi))
            return fmt::format("{}: expected {}..{}, got {}", name, lo, hi, *value);
        return std::nullopt;
    };
    if (auto e = out_of_range("--width", o.width, 1, kMaxImageSide)) return e;
    if (auto e = out_of_range("--height", o.height, 1, kMaxImageSide)) return e;
    if (auto e = out_of_range("--spp", o.spp, 1, kMaxSpp)) return e;
    if (auto e = out_of_range("--sampler-spp", o.sampler_spp, 1, kMaxSpp)) return e;
    if (auto e = out_of_range("--max-depth", o.max_depth, 1, kMaxDepth)) return e;
    if (auto e = out_of_range("--wave-size", o.wave_size, 1, 1LL << 26)) return e;
    if (o.time_limit && !(*o.time_limit > 0 && *o.time_limit < 1e9))
        return fmt::format("--time-limit: expected a positive number of seconds, got {}",
                           *o.time_limit);
    if (auto e = out_of_range("--sample-offset", o.sample_offset, 0, (1LL << 31) - kMaxSpp))
        return e;
    if (o.checkpoint_every && !(*o.checkpoint_every > 0 && *o.checkpoint_every < 1e9))
        return fmt::format("--checkpoint-every: expected a positive number of seconds, got {}",
                           *o.checkpoint_every);
    if (!use_simd_target(o.simd)) {
        std::string names;
        for (const std::string& t : simd_targets()) names += (names.empty() ? "" : ", ") + t;
        return fmt::format("--simd {}: not a target this CPU runs ({})", o.simd, names);
    }
    if (o.checkpoint_every && o.film.empty() && o.resume.empty())
        return std::string("--checkpoint-every: needs --film FILE (or --resume FILE) to write");
    if ((!o.film.empty() || !o.resume.empty()) && o.aov != "color")
        return std::string("--film/--resume: only light transport (--aov color) has a film");
    if (o.threads < 0)
        return fmt::format("--threads: expected a positive count, got {}", o.threads);
    if (!std::isfinite(o.exposure) || std::fabs(o.exposure) > 64)
        return fmt::format("--exposure: expected a number in [-64, 64], got {}", o.exposure);
    long long w = o.width.value_or(r.width), h = o.height.value_or(r.height);
    if (w * h > kMaxPixels)
        return fmt::format("{} x {} = {} pixels exceeds the limit of {}", w, h, w * h, kMaxPixels);
    return std::nullopt;
}

// Whether two names are one file: the same inode where both exist, else the same absolute
// path once `.` and `..` (and symbolic links of the folders that exist) are resolved.
bool same_file(const fs::path& a, const fs::path& b) {
    std::error_code ec;
    if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
    return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

// The files a render reads and writes must be distinct: an output named like the scene, or
// like another output, would destroy it. (--resume's film is rewritten on purpose unless
// --film names another file, which must then not be the scene either.)
std::optional<std::string> check_distinct_files(const RenderOptions& o, const fs::path& output) {
    std::vector<std::pair<std::string, fs::path>> outputs = {{"-o/--output", output}};
    if (!o.variance.empty()) outputs.push_back({"--variance", o.variance});
    if (!o.film.empty()) outputs.push_back({"--film", o.film});
    if (o.film.empty() && !o.resume.empty()) outputs.push_back({"--resume", o.resume});
    for (size_t i = 0; i < outputs.size(); ++i) {
        if (same_file(outputs[i].second, o.scene))
            return outputs[i].first + ": " + outputs[i].second.string() +
                   " is the scene file; writing it would destroy the scene";
        for (size_t j = 0; j < i; ++j)
            if (same_file(outputs[i].second, outputs[j].second))
                return outputs[i].first + " and " + outputs[j].first + " name the same file " +
                       outputs[i].second.string();
    }
    if (!o.film.empty() && !o.resume.empty() && same_file(o.resume, output))
        return "--resume: " + o.resume + " is the output image";
    return std::nullopt;
}

// What a render produced: the image, its metadata and the summary line; spp_done is -1 for
// renders that are not pass-based (AOVs).
struct Rendered {
    WriteOptions write;
    Image image;
    Image variance;  // of the pixel means, when --variance asks for it
    std::string summary;
    int spp_done = -1;
    std::string film_error;  // why the final film was not written; "" if it was (or none asked)
};

// The request of a colour render: every option that changes the samples (not yet their range).
RenderRequest color_request(const RenderOptions& o, const Scene& scene, int width, int height) {
    RenderRequest request;
    request.width = width;
    request.height = height;
    request.seed = o.seed;
    request.sampler = o.sampler ? *parse_sampler(*o.sampler) : scene.render.sampler;
    request.sampler_spp = static_cast<int>(o.sampler_spp.value_or(std::min<long long>(
        kMaxSpp, o.sample_offset.value_or(0) + o.spp.value_or(scene.render.spp))));
    request.engine = *parse_engine(o.engine);
    request.estimator.strategy = *parse_strategy(o.strategy);
    request.estimator.heuristic =
        o.heuristic == "balance" ? MisHeuristic::Balance : MisHeuristic::Power;
    request.estimator.max_depth = o.max_depth.value_or(scene.render.max_depth);
    if (o.wave_size) request.wavefront.wave_size = static_cast<size_t>(*o.wave_size);
    request.wavefront.sort_by_material = o.sort_by_material;
    request.wavefront.schedule = *parse_schedule(o.schedule);
    if (o.time_limit) request.time_limit = *o.time_limit;
    return request;
}

// What must match for two films to be parts of one render: the scene file's content and the
// request's settings.
std::string film_settings(const RenderOptions& o, const Scene& scene, int width, int height) {
    std::ifstream in(o.scene, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return wavetrace::film_settings(fnv1a_64(text.data(), text.size()),
                                    color_request(o, scene, width, height));
}

// The render itself: BVH, engine or AOV, the image and its metadata. `film_settings_text`: the film
// settings (film_settings); `resumed`: the film of --resume, already checked against them.
Rendered render_to_image(const RenderOptions& o,
                         const Scene& scene,
                         int width,
                         int height,
                         const fs::path& output,
                         const std::string& film_settings_text,
                         std::optional<std::pair<Film, FilmInfo>>& resumed) {
    Bvh bvh;
    try {
        bvh = Bvh::build(scene);
    } catch (const std::bad_alloc&) {
        throw OutOfMemory(fmt::format(
            "out of memory building the BVH of {} primitives; render on a machine with more "
            "memory",
            scene.primitive_count()));
    }
    Rendered r;
    WriteOptions& write = r.write;
    Image& image = r.image;
    std::string& summary = r.summary;
    write.exposure = o.exposure;
    write.metadata = {{"wavetrace:scene", o.scene}, {"wavetrace:seed", std::to_string(o.seed)}};
    if (o.aov == "color") {
        RenderRequest request = color_request(o, scene, width, height);
        // Samples [offset, offset + requested) in all; a resumed film holds the first ones.
        const int requested = o.spp.value_or(scene.render.spp);
        const uint32_t offset = static_cast<uint32_t>(o.sample_offset.value_or(0));
        const int already = resumed ? static_cast<int>(resumed->second.samples()) : 0;
        Film film = resumed ? std::move(resumed->first) : Film(width, height);
        request.first_sample = static_cast<int>(offset) + already;
        request.spp = std::max(0, requested - already);
        if (already > requested)
            std::cerr << fmt::format(
                "wavetrace: warning: {}: holds {} samples per pixel, more than --spp {}; nothing "
                "is rendered and the image is of the {}\n",
                o.resume, already, requested, already);
        // Checkpoints come between passes: passes no longer than half the interval.
        if (o.checkpoint_every)
            request.pass_seconds = std::min(request.pass_seconds, *o.checkpoint_every / 2);
        const fs::path film_path = !o.film.empty() ? fs::path(o.film) : fs::path(o.resume);
        auto film_info = [&](int done) {
            FilmInfo info{film_settings_text, {}};
            if (already + done > 0)
                info.ranges.push_back({offset, static_cast<uint32_t>(already + done)});
            return info;
        };

        // A checkpoint that cannot be written (a full disk) is a warning: the render goes on,
        // and the final film write tries again.
        RenderWatch watch(request, already, o.time_limit, o.checkpoint_every,
                          [&](const Film& f, int done) {
                              try {
                                  save_film(film_path, f, film_info(done));
                              } catch (const FilmError& e) {
                                  std::cerr << "\nwavetrace: warning: checkpoint not written: "
                                            << e.what() << "; the render goes on\n";
                              }
                          });
        std::signal(SIGINT, on_stop_signal);
        std::signal(SIGTERM, on_stop_signal);
        RenderStats stats;
        if (request.spp > 0) stats = render(scene, bvh, request, film, &watch);
        watch.finish();
        const int total = already + stats.spp_done;
        r.spp_done = total;
        // A film that cannot be written does not cost the image: it is written, and the exit
        // code says the film failed.
        if (!film_path.empty()) {
            try {
                save_film(film_path, film, film_info(stats.spp_done));
            } catch (const FilmError& e) {
                r.film_error = e.what();
            }
        }
        image = film.mean();
        if (!o.variance.empty()) r.variance = film.variance_of_mean();
        write.metadata.insert(write.metadata.end(),
                              {{"wavetrace:engine", o.engine},
                               {"wavetrace:strategy", o.strategy},
                               {"wavetrace:sampler", to_string(request.sampler)},
                               {"wavetrace:simd", simd_target()},
                               {"wavetrace:mis_heuristic", o.heuristic},
                               {"wavetrace:spp", std::to_string(total)},
                               {"wavetrace:spp_requested", std::to_string(requested)},
                               {"wavetrace:first_sample", std::to_string(offset)},
                               {"wavetrace:max_depth", std::to_string(request.estimator.max_depth)},
                               {"wavetrace:render_seconds", fmt::format("{:.3f}", stats.seconds)}});
        std::string stopped;
        if (total < requested)
            stopped = fmt::format(" of {} requested ({})", requested,
                                  g_stop_signal.load() == SIGINT    ? "interrupted"
                                  : g_stop_signal.load() == SIGTERM ? "terminated"
                                                                    : "time limit reached");
        const std::string resumed_note =
            already > 0 ? fmt::format(" ({} resumed, {} rendered)", already, stats.spp_done) : "";
        summary = fmt::format(
            "{} {}{} {}x{} {} spp{}{}: {:.2f} s, {:.2f} Mpaths/s, {:.2f} Mrays/s, "
            "{} invalid samples, peak memory {:.1f} MiB",
            o.engine, o.strategy,
            request.sampler == RenderRequest{}.sampler
                ? std::string()
                : " " + std::string(to_string(request.sampler)),
            width, height, total, stopped, resumed_note, stats.seconds,
            stats.seconds > 0 ? stats.paths / stats.seconds * 1e-6 : 0.0,
            stats.seconds > 0 ? stats.rays / stats.seconds * 1e-6 : 0.0, film.invalid_samples(),
            peak_rss_mib());
    } else {
        AovSettings settings{width, height, o.spp.value_or(1), o.seed};
        Aov aov = o.aov == "albedo" ? Aov::Albedo : o.aov == "normal" ? Aov::Normal : Aov::Depth;
        image = render_aov(scene, bvh, aov, settings);
        write.metadata.push_back({"wavetrace:aov", o.aov});
        write.metadata.push_back({"wavetrace:spp", std::to_string(settings.spp)});
        summary = fmt::format("{} {}x{} {} spp", o.aov, width, height, settings.spp);

        // 8-bit outputs cannot hold negative normals or unbounded depths: map them to [0, 1].
        if (is_ldr_path(output)) map_aov_to_display(aov, image);
    }
    return r;
}

}  // namespace

int run_render(const RenderOptions& o) {
    auto start = std::chrono::steady_clock::now();
    std::optional<tbb::global_control> threads;
    try {
        if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    } catch (const std::bad_alloc&) {
        std::cerr << "wavetrace: error: out of memory before reading the scene (setting up "
                  << o.threads << " threads)\n";
        return kExitBadInput;
    }

    fs::path output = o.output.empty() ? fs::path(fs::path(o.scene).stem().string() + ".png")
                                       : fs::path(o.output);
    Scene scene;
    try {
        // Every check that can fail before the render does: no render is wasted on an output
        // that cannot be written.
        if (auto clash = check_distinct_files(o, output)) throw SceneError(*clash);
        check_output_writable(output);
        if (!o.variance.empty()) {
            if (o.aov != "color")
                throw SceneError("--variance: only light transport (--aov color) has a variance");
            if (is_ldr_path(o.variance))
                throw SceneError("--variance: " + o.variance +
                                 ": a variance needs a linear float format (.exr, .hdr, .pfm)");
            check_output_writable(o.variance);
        }
        LoadOptions load;
        load.camera = o.camera;
        load.params = parse_defines(o.defines);
        load.asset_root = o.asset_root;
        scene = load_scene(o.scene, load);
        if (auto problem = check_options(o, scene.render)) throw SceneError(*problem);
    } catch (const std::bad_alloc&) {
        std::cerr << "wavetrace: error: " << o.scene
                  << ": out of memory loading the scene\n";
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    }

    const int width = o.width.value_or(scene.render.width);
    const int height = o.height.value_or(scene.render.height);
    // A film to resume must be of this render, and hold samples from --sample-offset on.
    std::optional<std::pair<Film, FilmInfo>> resumed;
    const std::string settings = o.aov == "color" ? film_settings(o, scene, width, height) : "";
    try {
        if (!o.resume.empty()) {
            resumed = load_film(o.resume);
            const std::string diff = settings_difference(resumed->second.settings, settings);
            if (!diff.empty())
                throw FilmError(o.resume + ": the film of another render (" + diff + ")");
            const auto& ranges = resumed->second.ranges;
            const uint32_t offset = static_cast<uint32_t>(o.sample_offset.value_or(0));
            if (ranges.size() > 1 || (ranges.size() == 1 && ranges[0].first != offset))
                throw FilmError(fmt::format(
                    "{}: holds samples [{}, {}){}, not a range from --sample-offset {}; merge "
                    "parts with `wavetrace merge`",
                    o.resume, ranges[0].first, ranges[0].end(),
                    ranges.size() > 1 ? " and more" : "", offset));
        }
        if (!o.film.empty()) check_output_writable(o.film + ".exr");  // the folder is writable
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    }
    Rendered r;
    try {
        r = render_to_image(o, scene, width, height, output, settings, resumed);
    } catch (const FilmError& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitFailure;
    } catch (const OutOfMemory& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const std::bad_alloc&) {
        // Say what the pixels cost and what would fit, instead of dying on SIGABRT.
        const double pixels = double(width) * height;
        const double film_mib = pixels * Film::kBytesPerPixel / (1 << 20);
        std::cerr << fmt::format(
            "wavetrace: error: out of memory rendering {} x {}, with the scene and its BVH in "
            "memory: the film takes {:.0f} MiB ({} bytes per pixel) besides the engine's "
            "queues and the image; render fewer pixels (--width/--height) or on a machine "
            "with more memory\n",
            width, height, film_mib, Film::kBytesPerPixel);
        return kExitBadInput;
    }
    // Stopped by a signal: exit as the shell expects of it (128 + signal), after writing
    // the image of the completed passes, if there are any.
    const int signal_exit = g_stop_signal.load() != 0 ? 128 + g_stop_signal.load() : 0;
    if (r.spp_done == 0) {
        std::cerr << "wavetrace: stopped before the first pass completed; no image written\n";
        return signal_exit != 0 ? signal_exit : kExitFailure;
    }
    try {
        write_image(output, r.image, r.write);
        if (!o.variance.empty()) {
            WriteOptions meta = r.write;
            meta.metadata.push_back({"wavetrace:content", "variance of the pixel means"});
            write_image(o.variance, r.variance, meta);
        }
    } catch (const ImageError& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitFailure;
    }
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << fmt::format("wavetrace: {} -> {} ({:.2f} s in all)\n", r.summary, output.string(),
                             seconds);
    std::cout << output.string() << "\n";
    if (!r.film_error.empty()) {
        std::cerr << "wavetrace: error: the image is written, the film is not: " << r.film_error
                  << "\n";
        return kExitFilmNotWritten;
    }
    return signal_exit != 0 ? signal_exit : kExitOk;
}

}  // namespace wavetrace::cli
