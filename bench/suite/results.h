// Benchmark results: named tables, saved as one CSV per table and all together as JSON.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

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

// Median, min and max of a sample.
struct Spread {
    double min, median, max;
};
Spread spread(std::vector<double> v);

}  // namespace wavetrace::bench
