// `wavetrace merge PART.film... -o OUT`: the render of all the parts' samples, from films of
// sample ranges of one render (render --sample-offset K --spp N --film PART.film).
#include <fmt/core.h>

#include <iostream>

#include "commands.h"
#include "wavetrace/film/film_file.h"
#include "wavetrace/image/image.h"

namespace wavetrace::cli {

void add_merge_command(CLI::App& app, MergeOptions& o) {
    CLI::App* cmd = app.add_subcommand(
        "merge",
        "merge films of sample ranges of one render (render --sample-offset --film) into its "
        "image, in any order; overlapping or mismatched parts are refused");
    cmd->add_option("parts", o.parts, "film files")->required();
    cmd->add_option("-o,--output", o.output, "the merged image (.exr, .png, ...)")->required();
    cmd->add_option("--film", o.film, "also write the merged film");
}

int run_merge(const MergeOptions& o) {
    std::vector<std::filesystem::path> parts(o.parts.begin(), o.parts.end());
    std::pair<Film, FilmInfo> merged;
    try {
        check_output_writable(o.output);
        if (!o.film.empty()) check_output_writable(o.film + ".exr");  // the folder is writable
        merged = merge_films(parts);
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitBadInput;
    }
    const auto& [film, info] = merged;
    std::string ranges;
    for (const SampleRange& r : info.ranges)
        ranges += fmt::format("{}[{}, {})", ranges.empty() ? "" : " ", r.first, r.end());
    WriteOptions write;
    write.metadata = {{"wavetrace:spp", std::to_string(info.samples())},
                      {"wavetrace:sample_ranges", ranges},
                      {"wavetrace:merged_parts", std::to_string(parts.size())}};
    try {
        write_image(o.output, film.mean(), write);
        if (!o.film.empty()) save_film(o.film, film, info);
    } catch (const std::exception& e) {
        std::cerr << "wavetrace: error: " << e.what() << "\n";
        return kExitFailure;
    }
    std::cerr << fmt::format("wavetrace: merged {} films: samples {} ({} spp) -> {}\n",
                             parts.size(), ranges, info.samples(), o.output);
    std::cout << o.output << "\n";
    return kExitOk;
}

}  // namespace wavetrace::cli
