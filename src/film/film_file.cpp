#include "wavetrace/film/film_file.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "files/input_file.h"
#include "files/output_file.h"
#include "wavetrace/scene/scene.h"

namespace wavetrace {
namespace fs = std::filesystem;

static_assert(std::endian::native == std::endian::little,
              "film files are little-endian and written as the machine holds them");

namespace {

constexpr char kMagic[16] = "wavetrace-film\n";  // 15 characters and a NUL
constexpr uint32_t kVersion = 1;
constexpr uint32_t kMaxSettingsBytes = 1 << 16;
constexpr uint32_t kMaxRanges = 1 << 20;

class Writer {
  public:
    template <class T>
    void put(const T& v) {
        const auto* p = reinterpret_cast<const unsigned char*>(&v);
        bytes.insert(bytes.end(), p, p + sizeof(T));
    }
    template <class T>
    void put_array(const std::vector<T>& v) {
        const auto* p = reinterpret_cast<const unsigned char*>(v.data());
        bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
    }
    std::vector<unsigned char> bytes;
};

class Reader {
  public:
    Reader(const std::vector<unsigned char>& b, const fs::path& path) : b_(b), path_(path) {}
    template <class T>
    T get() {
        T v;
        take(&v, sizeof(T));
        return v;
    }
    template <class T>
    void get_array(std::vector<T>& v, size_t n) {
        v.resize(n);
        take(v.data(), n * sizeof(T));
    }
    size_t at() const { return at_; }
    [[noreturn]] void fail(const std::string& what) const {
        throw FilmError(path_.string() + ": not a film file wavetrace can read: " + what);
    }

  private:
    void take(void* out, size_t n) {
        if (n == 0) return;  // an empty array: out may be null (found by tests/fuzz/fuzz_film)
        if (n > b_.size() - at_) fail("truncated");
        std::memcpy(out, b_.data() + at_, n);
        at_ += n;
    }
    const std::vector<unsigned char>& b_;
    const fs::path& path_;
    size_t at_ = 0;
};

// Sorts ranges, refuses overlaps, joins adjacent ones.
std::vector<SampleRange> normalized(std::vector<SampleRange> r) {
    std::sort(r.begin(), r.end(),
              [](const SampleRange& a, const SampleRange& b) { return a.first < b.first; });
    std::vector<SampleRange> out;
    for (const SampleRange& x : r) {
        if (x.count == 0) continue;
        if (!out.empty() && x.first < out.back().end())
            throw FilmError("sample ranges overlap: [" + std::to_string(out.back().first) + ", " +
                            std::to_string(out.back().end()) + ") and [" + std::to_string(x.first) +
                            ", " + std::to_string(x.end()) + ")");
        if (!out.empty() && x.first == out.back().end())
            out.back().count += x.count;
        else
            out.push_back(x);
    }
    return out;
}

}  // namespace

// Enough to tell a truncated or damaged file from a whole one.
uint64_t fnv1a_64(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    uint64_t h = 0xcbf29ce484222325ULL;
    for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
    return h;
}

uint32_t FilmInfo::samples() const {
    uint32_t n = 0;
    for (const SampleRange& r : ranges) n += r.count;
    return n;
}

void save_film(const fs::path& path, const Film& film, const FilmInfo& info) {
    Writer w;
    for (char c : kMagic) w.put(c);
    w.put(kVersion);
    w.put(static_cast<uint32_t>(film.width_));
    w.put(static_cast<uint32_t>(film.height_));
    w.put(static_cast<uint32_t>(info.settings.size()));
    w.bytes.insert(w.bytes.end(), info.settings.begin(), info.settings.end());
    w.put(static_cast<uint32_t>(info.ranges.size()));
    for (const SampleRange& r : info.ranges) {
        w.put(r.first);
        w.put(r.count);
    }
    w.put(film.invalid_.load());
    w.put_array(film.sum_);
    w.put_array(film.sum_sq_);
    w.put_array(film.counts_);
    w.put(fnv1a_64(w.bytes.data(), w.bytes.size()));
    try {
        write_file_atomically(path, w.bytes);
    } catch (const std::runtime_error& e) {
        throw FilmError(path.string() + ": " + e.what());
    }
}

std::pair<Film, FilmInfo> load_film(const fs::path& path) {
    const uint64_t max_bytes =
        4096 + kMaxSettingsBytes + 8ull * kMaxRanges + uint64_t(kMaxPixels) * Film::kBytesPerPixel;
    try {
        check_input_file(path, max_bytes, "film files");
    } catch (const std::exception& e) {
        throw FilmError(path.string() + ": " + e.what());
    }
    std::ifstream in(path, std::ios::binary);
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                     std::istreambuf_iterator<char>());
    Reader r(bytes, path);
    char magic[sizeof kMagic];
    for (char& c : magic) c = r.get<char>();
    if (std::memcmp(magic, kMagic, sizeof kMagic) != 0) r.fail("no film header");
    if (const uint32_t v = r.get<uint32_t>(); v != kVersion)
        r.fail("version " + std::to_string(v) + " (this wavetrace reads version " +
               std::to_string(kVersion) + ")");
    const uint32_t width = r.get<uint32_t>(), height = r.get<uint32_t>();
    if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide ||
        uint64_t(width) * height > kMaxPixels)
        r.fail("bad size " + std::to_string(width) + " x " + std::to_string(height));
    FilmInfo info;
    const uint32_t settings_bytes = r.get<uint32_t>();
    if (settings_bytes > kMaxSettingsBytes) r.fail("settings too long");
    std::vector<char> settings;
    r.get_array(settings, settings_bytes);
    info.settings.assign(settings.begin(), settings.end());
    const uint32_t ranges = r.get<uint32_t>();
    if (ranges > kMaxRanges) r.fail("too many sample ranges");
    for (uint32_t i = 0; i < ranges; ++i) {
        SampleRange s;
        s.first = r.get<uint32_t>();
        s.count = r.get<uint32_t>();
        if (uint64_t(s.first) + s.count > UINT32_MAX) r.fail("bad sample range");
        info.ranges.push_back(s);
    }
    try {
        if (normalized(info.ranges) != info.ranges) r.fail("sample ranges not in order");
    } catch (const FilmError& e) {
        r.fail(e.what());
    }
    // The file must hold exactly what its header announces, checked before the film is
    // allocated: a damaged header must not ask for gigabytes (found by tests/fuzz/fuzz_film).
    const size_t pixels = size_t(width) * height;
    const size_t expected =
        r.at() + sizeof(uint64_t) + pixels * Film::kBytesPerPixel + sizeof(uint64_t);
    if (bytes.size() != expected)
        r.fail(std::to_string(bytes.size()) + " bytes where its header announces " +
               std::to_string(expected) + " (truncated or damaged)");
    Film film(static_cast<int>(width), static_cast<int>(height));
    film.invalid_ = r.get<uint64_t>();
    r.get_array(film.sum_, 3 * pixels);
    r.get_array(film.sum_sq_, 3 * pixels);
    r.get_array(film.counts_, pixels);
    const size_t checked = r.at();
    if (r.get<uint64_t>() != fnv1a_64(bytes.data(), checked)) r.fail("checksum mismatch (damaged)");
    if (r.at() != bytes.size()) r.fail("trailing bytes");
    return {std::move(film), std::move(info)};
}

std::string settings_difference(const std::string& a, const std::string& b) {
    std::istringstream sa(a), sb(b);
    std::string la, lb;
    while (true) {
        const bool ga = static_cast<bool>(std::getline(sa, la));
        const bool gb = static_cast<bool>(std::getline(sb, lb));
        if (!ga && !gb) return "";
        if (!ga) la.clear();
        if (!gb) lb.clear();
        if (la != lb) {
            const std::string key = (ga ? la : lb).substr(0, (ga ? la : lb).find('='));
            auto value = [](const std::string& l) {
                auto eq = l.find('=');
                return eq == std::string::npos ? std::string("(none)") : l.substr(eq + 1);
            };
            return key + ": " + (ga ? value(la) : "(none)") + " vs " + (gb ? value(lb) : "(none)");
        }
    }
}

void merge_film(Film& into, FilmInfo& into_info, const Film& part, const FilmInfo& part_info) {
    if (part.width() != into.width() || part.height() != into.height())
        throw FilmError("films of different sizes: " + std::to_string(part.width()) + " x " +
                        std::to_string(part.height()) + " vs " + std::to_string(into.width()) +
                        " x " + std::to_string(into.height()));
    std::vector<SampleRange> all = into_info.ranges;
    all.insert(all.end(), part_info.ranges.begin(), part_info.ranges.end());
    into_info.ranges = normalized(all);  // throws on overlap, before anything is added
    into.merge(part);
}

std::pair<Film, FilmInfo> merge_films(std::vector<FilmPart> parts) {
    if (parts.empty()) throw FilmError("no films to merge");
    for (const FilmPart& p : parts) {
        const std::string diff = settings_difference(parts.front().info.settings, p.info.settings);
        if (!diff.empty())
            throw FilmError(p.name + ": not a part of the same render as " + parts.front().name +
                            " (" + diff + ")");
    }
    std::stable_sort(parts.begin(), parts.end(), [](const FilmPart& a, const FilmPart& b) {
        auto first = [](const FilmPart& p) {
            return p.info.ranges.empty() ? 0u : p.info.ranges[0].first;
        };
        return first(a) < first(b);
    });
    Film film(parts.front().film.width(), parts.front().film.height());
    FilmInfo info{parts.front().info.settings, {}};
    for (const FilmPart& p : parts) {
        try {
            merge_film(film, info, p.film, p.info);
        } catch (const FilmError& e) {
            throw FilmError(p.name + ": " + e.what());
        }
    }
    return {std::move(film), std::move(info)};
}

std::pair<Film, FilmInfo> merge_films(const std::vector<fs::path>& paths) {
    if (paths.empty()) throw FilmError("no films to merge");
    std::vector<FilmPart> parts;
    for (const fs::path& p : paths) {
        auto [film, info] = load_film(p);
        parts.push_back({p.string(), std::move(film), std::move(info)});
    }
    return merge_films(std::move(parts));
}

}  // namespace wavetrace
