// libFuzzer target: a film file (render --film, merge) through load_film, and, when it loads,
// reduced to an image and merged into an empty film, as `wavetrace merge` would.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "wavetrace/film/film_file.h"

namespace fs = std::filesystem;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const fs::path file =
        fs::temp_directory_path() / ("wavetrace-fuzz-film-" + std::to_string(::getpid()));
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        auto [film, info] = wavetrace::load_film(file);
        (void)film.mean();
        (void)film.variance_of_mean();
        wavetrace::Film merged(film.width(), film.height());
        wavetrace::FilmInfo merged_info{info.settings, {}};
        wavetrace::merge_film(merged, merged_info, film, info);
    } catch (const wavetrace::FilmError&) {
    }
    fs::remove(file);
    return 0;
}
