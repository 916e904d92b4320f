#include "results.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace wavetrace::bench {

void Results::table(const std::string& name, std::vector<std::string> columns) {
    tables_.push_back({name, std::move(columns), {}});
}

void Results::row(const std::string& name, std::vector<nlohmann::json> values) {
    for (Table& t : tables_)
        if (t.name == name) {
            if (values.size() != t.columns.size())
                throw std::logic_error("table " + name + ": row of " +
                                       std::to_string(values.size()) + " values for " +
                                       std::to_string(t.columns.size()) + " columns");
            t.rows.push_back(std::move(values));
        }
}

void Results::save(const std::filesystem::path& dir) const {
    std::filesystem::create_directories(dir);
    nlohmann::json all = {{"meta", meta_}, {"tables", nlohmann::json::object()}};
    for (const Table& t : tables_) {
        std::ofstream csv(dir / (t.name + ".csv"));
        for (size_t c = 0; c < t.columns.size(); ++c) csv << (c ? "," : "") << t.columns[c];
        csv << "\n";
        nlohmann::json rows = nlohmann::json::array();
        for (const auto& r : t.rows) {
            nlohmann::json obj;
            for (size_t c = 0; c < r.size(); ++c) {
                csv << (c ? "," : "") << (r[c].is_string() ? r[c].get<std::string>() : r[c].dump());
                obj[t.columns[c]] = r[c];
            }
            csv << "\n";
            rows.push_back(obj);
        }
        all["tables"][t.name] = rows;
    }
    std::ofstream(dir / "results.json") << all.dump(2) << "\n";
}

double relative_mse(const Image& a, const Image& ref) {
    double sum = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
        double x = luminance(a.pixels[i]), r = luminance(ref.pixels[i]);
        sum += (x - r) * (x - r) / (r * r + 1e-3);
    }
    return sum / double(a.pixels.size());
}

Spread spread(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    if (v.empty()) return {0, 0, 0};
    return {v.front(), v[v.size() / 2], v.back()};
}

}  // namespace wavetrace::bench
