#include "pbrt/params.h"

#include <algorithm>
#include <cmath>

#include "wavetrace/scene/scene.h"

namespace wavetrace {

void PbrtParams::fail(const PbrtParam& p, const std::string& message) const {
    throw SceneError(p.place + ": " + what + ": \"" + p.name + "\" " + message);
}

PbrtParam* PbrtParams::get(const std::string& name) {
    for (PbrtParam& p : list)
        if (p.name == name) {
            p.used = true;
            return &p;
        }
    return nullptr;
}

double PbrtParams::number(const std::string& name, double fallback) {
    PbrtParam* p = get(name);
    if (!p) return fallback;
    if (p->numbers.size() != 1 || (p->type != "float" && p->type != "integer"))
        fail(*p, "should be one float");
    return p->numbers[0];
}

int PbrtParams::integer(const std::string& name, int fallback, int lo, int hi) {
    PbrtParam* p = get(name);
    if (!p) return fallback;
    if (p->numbers.size() != 1 || p->type != "integer") fail(*p, "should be one integer");
    const double v = p->numbers[0];
    if (!(v >= lo && v <= hi) || v != std::floor(v))
        fail(*p, "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return static_cast<int>(v);
}

bool PbrtParams::boolean(const std::string& name, bool fallback) {
    PbrtParam* p = get(name);
    if (!p) return fallback;
    if (p->bools.size() != 1) fail(*p, "should be one bool");
    return p->bools[0];
}

std::string PbrtParams::string(const std::string& name, const std::string& fallback) {
    PbrtParam* p = get(name);
    if (!p) return fallback;
    if (p->strings.size() != 1 || (p->type != "string" && p->type != "texture"))
        fail(*p, "should be one string");
    return p->strings[0];
}

std::array<double, 3> PbrtParams::triple(const std::string& name, std::array<double, 3> fallback) {
    PbrtParam* p = get(name);
    if (!p) return fallback;
    if (p->numbers.size() != 3) fail(*p, "should be three numbers");
    return {p->numbers[0], p->numbers[1], p->numbers[2]};
}

const std::vector<double>* PbrtParams::numbers(const std::string& name, size_t arity) {
    PbrtParam* p = get(name);
    if (!p) return nullptr;
    if (!p->strings.empty() || !p->bools.empty()) fail(*p, "should hold numbers");
    if (p->numbers.size() % arity != 0)
        fail(*p, "should hold a multiple of " + std::to_string(arity) + " numbers, got " +
                     std::to_string(p->numbers.size()));
    return &p->numbers;
}

void PbrtParams::finish(const Warn& warn, std::initializer_list<const char*> quiet) {
    for (const PbrtParam& p : list) {
        if (p.used) continue;
        if (std::find_if(quiet.begin(), quiet.end(), [&](const char* q) { return p.name == q; }) !=
            quiet.end())
            continue;
        warn(p.place, what + ": parameter \"" + p.name + "\" is not supported; ignored");
    }
}

}  // namespace wavetrace
