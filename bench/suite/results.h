// Benchmark results: named tables, saved as one CSV per table and all together as JSON.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "wavetrace/image/image.h"

namespace wavetrace::bench {

class Results {
  public:
    // Starts a table; each later row() call adds values in the columns' order.
    void table(const std::string& name, std::vector<std::string> columns);
    void row(const std::string& name, std::vector<nlohmann::json> values);
    void note(const std::string& key, nlohmann::json value) { meta_[key] = std::move(value); }
    // Writes DIR/NAME.csv per table and DIR/results.json.
    void save(const std::filesystem::path& dir) const;

  private:
    struct Table {
        std::string name;
        std::vector<std::string> columns;
        std::vector<std::vector<nlohmann::json>> rows;
    };
    std::vector<Table> tables_;
    nlohmann::json meta_ = nlohmann::json::object();
};

// Relative MSE of an image against a reference, per pixel (x - r)^2 / (r^2 + 1e-3) on
// luminance, averaged: the error measure of the engines and convergence sections.
double relative_mse(const wavetrace::Image& image, const wavetrace::Image& reference);

// Median, min and max of a sample.
struct Spread {
    double min, median, max;
};
Spread spread(std::vector<double> v);

}  // namespace wavetrace::bench
