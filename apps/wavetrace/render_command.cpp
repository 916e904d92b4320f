#include <fmt/core.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <optional>

#include "commands.h"
#include "wavetrace/wavetrace.h"

namespace wavetrace::cli {
namespace fs = std::filesystem;

void add_render_command(CLI::App& app, RenderOptions& o) {
    CLI::App* cmd = app.add_subcommand("render", "render a scene file to an image");
    cmd->add_option("scene", o.scene, "scene file (JSON)")->required();
    cmd->add_option("-o,--output", o.output,
                    "output image: .png/.jpg (8-bit sRGB) or .exr/.hdr/.pfm (linear float); "
                    "default: <scene>.png");
    cmd->add_option("--width", o.width, "image width in pixels (default: the scene's)");
    cmd->add_option("--height", o.height, "image height in pixels (default: the scene's)");
    cmd->add_option("--spp", o.spp, "samples per pixel (default: the scene's)");
    cmd->add_option("--seed", o.seed, "random seed")->capture_default_str();
    cmd->add_option("--threads", o.threads, "worker threads (default: all)");
    cmd->add_option("--aov", o.aov, "what to render")
        ->check(CLI::IsMember({"color", "albedo", "normal", "depth"}))
        ->capture_default_str();
    cmd->add_option("--exposure", o.exposure, "exposure in stops for .png/.jpg output")
        ->capture_default_str();
}

namespace {

// Range checks shared by all numeric options: each failure names the option.
std::optional<std::string> check_options(const RenderOptions& o, const RenderSettings& r) {
    if (o.width < 0 || o.width > kMaxImageSide)
        return fmt::format("--width: expected 1..{}, got {}", kMaxImageSide, o.width);
    if (o.height < 0 || o.height > kMaxImageSide)
        return fmt::format("--height: expected 1..{}, got {}", kMaxImageSide, o.height);
    if (o.spp < 0 || o.spp > kMaxSpp)
        return fmt::format("--spp: expected 1..{}, got {}", kMaxSpp, o.spp);
    if (o.threads < 0) return fmt::format("--threads: expected a positive count, got {}", o.threads);
    if (!std::isfinite(o.exposure) || std::fabs(o.exposure) > 64)
        return fmt::format("--exposure: expected a number in [-64, 64], got {}", o.exposure);
    long long w = o.width ? o.width : r.width, h = o.height ? o.height : r.height;
    if (w * h > kMaxPixels)
        return fmt::format("{} x {} = {} pixels exceeds the limit of {}", w, h, w * h, kMaxPixels);
    return std::nullopt;
}

}  // namespace

int run_render(const RenderOptions& o) {
    auto start = std::chrono::steady_clock::now();
    std::optional<tbb::global_control> threads;
    if (o.threads > 0) threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);

    if (o.aov == "color") {
        std::cerr << "wavetrace: error: --aov color needs a light-transport engine, and this build "
                     "has none yet; use --aov albedo, normal or depth\n";
        return kExitBadInput;
    }
    fs::path output =
        o.output.empty() ? fs::path(fs::path(o.scene).stem().string() + ".png") : fs::path(o.output);
    Scene scene;
    try {
        check_output_path(output);
        fs::path dir = output.parent_path();
        std::error_code ec;
        if (!dir.empty() && !fs::is_directory(dir, ec))
            throw ImageError(output.string() + ": folder '" + dir.string() + "' does not exist");
        scene = load_scene(o.scene);
        if (auto problem = check_options(o, scene.render)) throw SceneError(*problem);
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    }

    AovSettings settings;
    settings.width = o.width ? o.width : scene.render.width;
    settings.height = o.height ? o.height : scene.render.height;
    settings.spp = o.spp ? o.spp : 1;
    settings.seed = o.seed;
    Aov aov = o.aov == "albedo" ? Aov::Albedo : o.aov == "normal" ? Aov::Normal : Aov::Depth;

    Bvh bvh = Bvh::build(scene);
    Image image = render_aov(scene, bvh, aov, settings);

    // 8-bit outputs cannot hold negative normals or unbounded depths: map them to [0, 1].
    if (is_ldr_path(output)) {
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
    WriteOptions write;
    write.exposure = o.exposure;
    write.metadata = {{"wavetrace:scene", o.scene},
                      {"wavetrace:aov", o.aov},
                      {"wavetrace:spp", std::to_string(settings.spp)},
                      {"wavetrace:seed", std::to_string(o.seed)}};
    try {
        write_image(output, image, write);
    } catch (const ImageError& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitFailure;
    }
    double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << fmt::format("wavetrace: {} {}x{} {} spp -> {} ({:.2f} s)\n", o.aov, settings.width,
                             settings.height, settings.spp, output.string(), seconds);
    std::cout << output.string() << "\n";
    return kExitOk;
}

}  // namespace wavetrace::cli
