// The subcommands of the `wavetrace` command line. Each registers its options on a CLI11
// subcommand and runs from a plain options struct; bad input exits with kExitBadInput.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wavetrace::cli {

// -D NAME=VALUE options as a map (a later NAME wins); throws std::invalid_argument for an
// option without '=' or with an empty name.
inline std::map<std::string, std::string> parse_defines(const std::vector<std::string>& defines) {
    std::map<std::string, std::string> out;
    for (const std::string& d : defines) {
        const size_t eq = d.find('=');
        if (eq == std::string::npos || eq == 0)
            throw std::invalid_argument("-D " + d + ": expected NAME=VALUE");
        out[d.substr(0, eq)] = d.substr(eq + 1);
    }
    return out;
}

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   // the render or the write failed; compare: differs
inline constexpr int kExitBadInput = 2;  // bad scene, bad option: nothing was written
inline constexpr int kExitFilmNotWritten = 3;  // render: the image is written, the film is not

struct RenderOptions {
    std::string scene;
    std::string camera;  // a glTF scene's camera, by name
    std::vector<std::string> defines;  // a Mitsuba scene's parameters, NAME=VALUE
    std::string asset_root;            // every file read must lie inside it ("": anywhere)
    std::string output;
    // Not given: the scene file's value (or the engine's default, for the wave size).
    std::optional<int> width, height, spp, max_depth;
    std::optional<long long> wave_size;
    bool sort_by_material = false;
    std::string schedule = "resident";
    std::optional<double> time_limit;        // seconds: start no pass after this
    std::string variance;                    // where to write the variance of the pixel means
    std::string film;                        // where to write the film file (sums) at the end
    std::string resume;                      // a film file to continue
    std::optional<double> checkpoint_every;  // seconds between film refreshes
    std::optional<long long> sample_offset;  // first sample of the range rendered
    uint64_t seed = 0;
    int threads = 0;  // 0: all hardware threads
    std::string aov = "color";
    float exposure = 0.0f;
    std::string engine = "wavefront";
    std::string strategy = "mis";
    std::string heuristic = "power";
    std::optional<std::string> sampler;  // default: the scene's
    std::optional<long long> sampler_spp;  // zsobol's layout; default: offset + spp
    std::string simd;                     // "": the best target
};

struct CompareOptions {
    std::string ours, ref, ours_var, ref_var, z_map;
    int block = 8;
    double alpha = 0.01;
    double max_mean_diff = 1e-2;
    double max_rel_mse = 1e-2;
};

struct MergeOptions {
    std::vector<std::string> parts;
    std::string output;
    std::string film;
};

struct ConvertOptions {
    std::string scene;
    std::string output;
    std::vector<std::string> defines;
    std::string asset_root;
};

struct InfoOptions {
    std::string scene;
    std::vector<std::string> defines;
    std::string asset_root;
    int threads = 0;
};

void add_render_command(CLI::App& app, RenderOptions& options);
void add_convert_command(CLI::App& app, ConvertOptions& options);
int run_convert(const ConvertOptions& options);
void add_info_command(CLI::App& app, InfoOptions& options);
void add_compare_command(CLI::App& app, CompareOptions& options);
void add_merge_command(CLI::App& app, MergeOptions& options);
int run_merge(const MergeOptions& options);
int run_compare(const CompareOptions& options);
int run_render(const RenderOptions& options);
int run_info(const InfoOptions& options);

}  // namespace wavetrace::cli
