#include "wavetrace/film/film.h"

#include <cmath>
#include <stdexcept>

#include "util/check.h"

namespace wavetrace {

Film::Film(int width, int height)
    : width_(width),
      height_(height),
      sum_(static_cast<size_t>(width) * height * 3, 0.0),
      sum_sq_(static_cast<size_t>(width) * height * 3, 0.0),
      counts_(static_cast<size_t>(width) * height, 0) {}

void Film::add(int pixel, Color v) {
    WT_DCHECK(pixel >= 0 && static_cast<size_t>(pixel) < counts_.size());
    if (!is_finite(v) || v.x < 0 || v.y < 0 || v.z < 0) {
        invalid_.fetch_add(1, std::memory_order_relaxed);
        return;
    }
    for (int c = 0; c < 3; ++c) {
        sum_[3 * static_cast<size_t>(pixel) + c] += v[c];
        sum_sq_[3 * static_cast<size_t>(pixel) + c] += double(v[c]) * v[c];
    }
    ++counts_[pixel];
}

void Film::merge(const Film& other) {
    if (other.width_ != width_ || other.height_ != height_)
        throw std::invalid_argument("films of different sizes cannot be merged");
    for (size_t i = 0; i < sum_.size(); ++i) {
        sum_[i] += other.sum_[i];
        sum_sq_[i] += other.sum_sq_[i];
    }
    for (size_t i = 0; i < counts_.size(); ++i) counts_[i] += other.counts_[i];
    invalid_ += other.invalid_.load();
}

Image Film::mean() const {
    Image img(width_, height_);
    for (size_t i = 0; i < counts_.size(); ++i) {
        double n = std::max<uint32_t>(1, counts_[i]);
        img.pixels[i] = {float(sum_[3 * i] / n), float(sum_[3 * i + 1] / n),
                         float(sum_[3 * i + 2] / n)};
    }
    return img;
}

Image Film::variance_of_mean() const {
    Image img(width_, height_);
    for (size_t i = 0; i < counts_.size(); ++i) {
        double n = counts_[i];
        if (n < 2) continue;
        Color v;
        for (int c = 0; c < 3; ++c) {
            double m = sum_[3 * i + c] / n;
            double s2 = std::max(0.0, (sum_sq_[3 * i + c] - n * m * m) / (n - 1));
            v[c] = float(s2 / n);
        }
        img.pixels[i] = v;
    }
    return img;
}

}  // namespace wavetrace
