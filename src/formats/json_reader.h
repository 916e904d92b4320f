// Strict, located reading of JSON scene files: every value knows its file and JSON pointer,
// so that each error names the place ("x.json: /objects/3/radius: expected ..."), and every
// object checks that no key was left unread (typos are errors, not silently ignored).
#pragma once

#include <filesystem>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "wavetrace/math/vec3.h"

namespace wavetrace::json_reader {

using nlohmann::json;

class Value {
  public:
    Value(const json& j, const std::string& file, std::string pointer)
        : j_(&j), file_(&file), pointer_(std::move(pointer)) {}

    [[noreturn]] void fail(const std::string& message) const;
    const json& raw() const { return *j_; }
    const std::string& pointer() const { return pointer_; }
    const std::string& file() const { return *file_; }
    std::string describe() const;  // the value, shortened, for messages

    bool is_number() const { return j_->is_number(); }
    bool is_string() const { return j_->is_string(); }
    bool is_array() const { return j_->is_array(); }
    bool is_object() const { return j_->is_object(); }

    float number() const;                      // any finite number
    float positive() const;                    // finite, > 0
    float non_negative() const;                // finite, >= 0
    float in_range(float lo, float hi) const;  // finite, lo <= x <= hi
    int integer(int lo, int hi) const;
    bool boolean() const;
    std::string string() const;
    Vec3 vec3() const;          // [x, y, z], finite
    Vec3 color() const;         // [r, g, b] or a number, each finite and >= 0
    Vec3 reflectance() const;   // a color() with every component <= 1
    Vec3 nonzero_vec3() const;  // finite and not all zero

    size_t size() const;  // array length; fails if not an array
    Value operator[](size_t i) const;

  private:
    const json* j_;
    const std::string* file_;
    std::string pointer_;
};

// A JSON object whose keys are read one by one; finish() rejects the keys nobody read.
class Object {
  public:
    explicit Object(const Value& v);

    std::optional<Value> optional(const std::string& key);
    Value required(const std::string& key);
    bool has(const std::string& key) const { return v_.raw().contains(key); }
    const Value& value() const { return v_; }
    // Fails on the first key not in `known`, before anything is read: for objects whose
    // misspelt keys would otherwise surface later as confusing errors.
    void only(std::initializer_list<const char*> known) const;
    void finish() const;

  private:
    Value v_;
    std::vector<std::string> read_;
};

// Arrays and objects nest at most this deep in a scene file (groups, textures in textures).
inline constexpr int kMaxNesting = 64;

// Empties `j` depth first and frees it without allocating. nlohmann's own destructor moves a
// container's elements onto a heap-allocated stack before freeing them (so that deep nesting
// cannot overflow the call stack); out of memory, that allocation throws from a destructor and
// ends the process. Documents from parse() nest at most kMaxNesting deep, so recursion is safe.
void release(json& j) noexcept;

// A parsed document that release()s its tree when destroyed: a scene that ran out of memory
// while being read fails with an error, not std::terminate.
struct Document {
    json root;

    Document() = default;
    Document(Document&& d) noexcept : root(std::move(d.root)) {}
    Document& operator=(const Document&) = delete;
    ~Document() { release(root); }
};

// Parses `text` from `file`; syntax errors and nesting beyond kMaxNesting become SceneErrors
// with line and column. If it runs out of memory, std::bad_alloc leaves it with what it had
// read freed by release().
Document parse(const std::string& text, const std::string& file);

}  // namespace wavetrace::json_reader
