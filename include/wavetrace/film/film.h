// Per-pixel sums of samples in double precision, with sums of squares for the per-pixel
// sample variance that statistical tests and convergence measurements use.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "wavetrace/image/image.h"

namespace wavetrace {

struct FilmInfo;  // film_file.h: film files are written and read there

class Film {
  public:
    // Memory per pixel: sums and sums of squares (3 doubles each) and a sample count.
    static constexpr size_t kBytesPerPixel = 6 * sizeof(double) + sizeof(uint32_t);

    Film() = default;
    Film(int width, int height);
    Film(Film&& other) noexcept { *this = std::move(other); }
    Film& operator=(Film&& other) noexcept {
        width_ = other.width_;
        height_ = other.height_;
        sum_ = std::move(other.sum_);
        sum_sq_ = std::move(other.sum_sq_);
        counts_ = std::move(other.counts_);
        invalid_.store(other.invalid_.load());
        return *this;
    }

    int width() const { return width_; }
    int height() const { return height_; }

    // Adds one sample to a pixel. A pixel must be written by one thread at a time, in a fixed
    // order, for the result to be reproducible; non-finite or negative samples are not added
    // but counted (they would mean a bug).
    void add(int pixel, Color value);

    Image mean() const;
    // The variance of each pixel's mean, per channel: s^2 / n with s^2 the unbiased sample
    // variance of its samples.
    Image variance_of_mean() const;
    uint32_t samples(int pixel) const { return counts_[pixel]; }
    uint64_t invalid_samples() const { return invalid_.load(); }

    // Adds another film's sums, squares, counts and invalid samples, pixel by pixel (same
    // size; std::invalid_argument otherwise).
    void merge(const Film& other);

  private:
    friend void save_film(const std::filesystem::path&, const Film&, const FilmInfo&);
    friend std::pair<Film, FilmInfo> load_film(const std::filesystem::path&);

    int width_ = 0, height_ = 0;
    std::vector<double> sum_, sum_sq_;  // 3 per pixel
    std::vector<uint32_t> counts_;
    std::atomic<uint64_t> invalid_{0};
};

}  // namespace wavetrace
