// The parameter list of a pbrt-v4 directive: "type name" value pairs, read by the directive
// that owns them; a parameter it does not read is a warning.
#pragma once

#include <array>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

namespace wavetrace {

struct PbrtParam {
    std::string type, name;  // the type as pbrt-v4 spells it ("point3" for "point")
    std::vector<double> numbers;
    std::vector<std::string> strings;
    std::vector<bool> bools;
    std::string place;  // where it was written: "scene.pbrt:12"
    bool used = false;
};

class PbrtParams {
  public:
    using Warn = std::function<void(const std::string& place, const std::string& message)>;

    std::vector<PbrtParam> list;
    std::string what;  // the directive, for messages: "Shape \"sphere\""

    // The parameter of that name, marked as read; nullptr if absent.
    PbrtParam* get(const std::string& name);
    // Typed values with pbrt's defaults; a value of the wrong kind throws SceneError.
    double number(const std::string& name, double fallback);
    int integer(const std::string& name, int fallback, int lo, int hi);
    bool boolean(const std::string& name, bool fallback);
    std::string string(const std::string& name, const std::string& fallback);
    std::array<double, 3> triple(const std::string& name, std::array<double, 3> fallback);
    // Every `type name` of numbers, checked to hold a multiple of `arity` values.
    const std::vector<double>* numbers(const std::string& name, size_t arity);
    // A warning for each parameter nobody read, but those in `quiet`.
    void finish(const Warn& warn, std::initializer_list<const char*> quiet = {});

    [[noreturn]] void fail(const PbrtParam& p, const std::string& message) const;
};

}  // namespace wavetrace
