#pragma once

#include <string>
#include <vector>

#include "wavetrace/loaders/load_scene.h"

// The warnings of the last load that used collecting() (a test at a time), and a test of them.
inline std::vector<std::string> warnings;

inline wavetrace::LoadOptions collecting() {
    warnings.clear();
    wavetrace::LoadOptions o;
    o.warn = [](const std::string& w) { warnings.push_back(w); };
    return o;
}

inline bool warned(const std::string& part) {
    for (const std::string& w : warnings)
        if (w.find(part) != std::string::npos) return true;
    return false;
}
