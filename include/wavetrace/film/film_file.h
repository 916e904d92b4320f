// Film files: a render's per-pixel sums saved with what they are sums of, so that a render
// can be resumed (bit-identical to one that was never stopped) or merged with renders of other
// sample ranges of the same sequence. The format is in docs/film-format.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "wavetrace/film/film.h"

namespace wavetrace {

class FilmError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Samples [first, first + count) of every pixel's sequence.
struct SampleRange {
    uint32_t first = 0, count = 0;
    uint32_t end() const { return first + count; }
    bool operator==(const SampleRange&) const = default;
};

struct FilmInfo {
    // What must match for two films to be parts of one render: "key=value" lines (the scene
    // file's content hash, image size, seed, strategy, ...), compared as text.
    std::string settings;
    // The sample ranges the film's sums hold: sorted, disjoint, adjacent ones joined.
    std::vector<SampleRange> ranges;

    uint32_t samples() const;
};

// Writes the film atomically (FilmError naming the file on failure).
void save_film(const std::filesystem::path& path, const Film& film, const FilmInfo& info);
// Reads a film file, checking its magic, version, sizes and checksum (FilmError naming the
// file and what is wrong).
std::pair<Film, FilmInfo> load_film(const std::filesystem::path& path);

// FNV-1a, 64 bits: the films' checksum, and the scene file's fingerprint in their settings.
uint64_t fnv1a_64(const void* data, size_t bytes);

// The first settings line that differs between two films' settings, as "key: A vs B"; "" if
// they are the same.
std::string settings_difference(const std::string& a, const std::string& b);

// Adds `part` to `into`: the ranges must not overlap (FilmError otherwise). Parts are added in
// the order given; merge_films() below fixes that order.
void merge_film(Film& into, FilmInfo& into_info, const Film& part, const FilmInfo& part_info);

// A film held in memory with what it is of; `name` stands for it in messages (e.g. its file).
struct FilmPart {
    std::string name;
    Film film;
    FilmInfo info;
};

// Merges films of one render (same settings, disjoint ranges) in order of their first sample,
// so that any order of the parts gives the same bits. Throws FilmError naming the part that
// does not fit.
std::pair<Film, FilmInfo> merge_films(std::vector<FilmPart> parts);

// The same for film files, each named by its path (FilmError naming the file that cannot be
// read or does not fit).
std::pair<Film, FilmInfo> merge_films(const std::vector<std::filesystem::path>& paths);

}  // namespace wavetrace
