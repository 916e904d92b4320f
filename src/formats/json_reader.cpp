#include "formats/json_reader.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "wavetrace/scene/scene.h"

namespace wavetrace::json_reader {
namespace {

// JSON pointer escaping (RFC 6901): '~' -> "~0", '/' -> "~1".
std::string escape(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

}  // namespace

void Value::fail(const std::string& message) const {
    throw SceneError(*file_ + ": " + (pointer_.empty() ? "/" : pointer_) + ": " + message);
}

namespace {

// A JSON value written out up to about `budget` characters, without ever writing out (or
// recursing through) more of a large or deep value than that.
void describe_into(const json& j, size_t budget, std::string& out) {
    if (out.size() >= budget) return;
    if (j.is_array() || j.is_object()) {
        out += j.is_array() ? '[' : '{';
        bool first = true;
        for (auto it = j.begin(); it != j.end(); ++it) {
            if (out.size() >= budget) break;
            if (!first) out += ",";
            first = false;
            if (j.is_object()) out += json(it.key()).dump() + ":";
            describe_into(*it, budget, out);
        }
        out += j.is_array() ? ']' : '}';
        return;
    }
    out += j.dump();
}

}  // namespace

std::string Value::describe() const {
    std::string s;
    describe_into(*j_, 40, s);
    if (s.size() > 40) s = s.substr(0, 37) + "...";
    return s;
}

float Value::number() const {
    if (!j_->is_number()) fail("expected a number, got " + describe());
    double d = j_->get<double>();
    if (!std::isfinite(d) || std::fabs(d) > std::numeric_limits<float>::max())
        fail("expected a finite number, got " + describe());
    return static_cast<float>(d);
}

float Value::positive() const {
    if (!j_->is_number()) fail("expected a positive number, got " + describe());
    float x = number();
    if (!(x > 0.0f)) fail("expected a positive number, got " + describe());
    return x;
}

float Value::non_negative() const {
    if (!j_->is_number()) fail("expected a non-negative number, got " + describe());
    float x = number();
    if (!(x >= 0.0f)) fail("expected a non-negative number, got " + describe());
    return x;
}

float Value::in_range(float lo, float hi) const {
    auto range = [&] {
        return "expected a number in [" + nlohmann::json(lo).dump() + ", " +
               nlohmann::json(hi).dump() + "], got " + describe();
    };
    if (!j_->is_number()) fail(range());
    float x = number();
    if (!(x >= lo && x <= hi)) fail(range());
    return x;
}

int Value::integer(int lo, int hi) const {
    auto range = [&] {
        return "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
               "], got " + describe();
    };
    if (!j_->is_number_integer()) fail(range());
    long long x =
        j_->is_number_unsigned()
            ? static_cast<long long>(std::min<uint64_t>(j_->get<uint64_t>(), uint64_t(1) << 62))
            : j_->get<long long>();
    if (x < lo || x > hi) fail(range());
    return static_cast<int>(x);
}

bool Value::boolean() const {
    if (!j_->is_boolean()) fail("expected true or false, got " + describe());
    return j_->get<bool>();
}

std::string Value::string() const {
    if (!j_->is_string()) fail("expected a string, got " + describe());
    return j_->get<std::string>();
}

size_t Value::size() const {
    if (!j_->is_array()) fail("expected an array, got " + describe());
    return j_->size();
}

Value Value::operator[](size_t i) const {
    return Value((*j_)[i], *file_, pointer_ + "/" + std::to_string(i));
}

Vec3 Value::vec3() const {
    if (!j_->is_array() || j_->size() != 3)
        fail("expected an array of 3 numbers, got " + describe());
    return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
}

Vec3 Value::color() const {
    if (j_->is_number()) return Vec3(non_negative());
    if (!j_->is_array() || j_->size() != 3)
        fail("expected a colour [r, g, b] or a number, got " + describe());
    return {(*this)[0].non_negative(), (*this)[1].non_negative(), (*this)[2].non_negative()};
}

Vec3 Value::reflectance() const {
    Vec3 c = color();
    if (max_component(c) > 1.0f)
        fail("expected a reflectance with components in [0, 1], got " + describe());
    return c;
}

Vec3 Value::nonzero_vec3() const {
    Vec3 v = vec3();
    if (v.x == 0 && v.y == 0 && v.z == 0) fail("expected a non-zero vector, got " + describe());
    return v;
}

Object::Object(const Value& v) : v_(v) {
    if (!v.is_object()) v.fail("expected an object, got " + v.describe());
}

std::optional<Value> Object::optional(const std::string& key) {
    read_.push_back(key);
    auto it = v_.raw().find(key);
    if (it == v_.raw().end() || it->is_null()) return std::nullopt;
    return Value(*it, v_.file(), v_.pointer() + "/" + escape(key));
}

Value Object::required(const std::string& key) {
    auto v = optional(key);
    if (v) return *v;
    std::string hint;
    for (const auto& [present, unused] : v_.raw().items())
        if (edit_distance(present, key) <= 2) hint = " (is \"" + present + "\" a typo?)";
    v_.fail("missing required key \"" + key + "\"" + hint);
}

void Object::only(std::initializer_list<const char*> known) const {
    Object check(v_);
    for (const char* k : known) check.read_.push_back(k);
    check.finish();
}

void Object::finish() const {
    for (const auto& [key, value] : v_.raw().items()) {
        if (std::find(read_.begin(), read_.end(), key) != read_.end()) continue;
        std::string hint;
        size_t best = 3;
        for (const std::string& known : read_) {
            size_t d = edit_distance(key, known);
            if (d < best) {
                best = d;
                hint = " (did you mean \"" + known + "\"?)";
            }
        }
        if (hint.empty() && !read_.empty()) {
            hint = " (expected one of:";
            for (const std::string& known : read_) hint += " " + known;
            hint += ")";
        }
        Value(value, v_.file(), v_.pointer() + "/" + escape(key)).fail("unknown key" + hint);
    }
}

namespace {

// ":LINE:COLUMN" of the character at `offset` of `text`, both from 1.
std::string line_column(const std::string& text, size_t offset) {
    size_t line = 1, col = 1;
    for (size_t i = 0; i < offset && i < text.size(); ++i) {
        if (text[i] == '\n') {
            ++line;
            col = 1;
        } else {
            ++col;
        }
    }
    return ":" + std::to_string(line) + ":" + std::to_string(col);
}

// nlohmann's SAX interface building the tree as its DOM parser does, but owning it in a
// Document: an exception (std::bad_alloc above all) mid-parse frees the partial tree through
// release(), where nlohmann's parser would free it by the allocating destructor.
class TreeBuilder {
  public:
    Document root;

    bool null() { return add(nullptr); }
    bool boolean(bool b) { return add(b); }
    bool number_integer(json::number_integer_t n) { return add(n); }
    bool number_unsigned(json::number_unsigned_t n) { return add(n); }
    bool number_float(json::number_float_t x, const json::string_t&) { return add(x); }
    bool string(json::string_t& s) { return add(std::move(s)); }
    bool binary(json::binary_t& b) { return add(std::move(b)); }
    bool start_object(size_t) { return open(json::object()); }
    bool key(json::string_t& k) {
        // A repeated key keeps its last value, as nlohmann's DOM parser does.
        slot_ = &open_.back()->get_ref<json::object_t&>()[k];
        return true;
    }
    bool end_object() { return close(); }
    bool start_array(size_t) { return open(json::array()); }
    bool end_array() { return close(); }
    template <class Exception>
    bool parse_error(size_t, const std::string&, const Exception& e) {
        throw e;  // by its own type: json::parse_error keeps its byte offset
    }

  private:
    // Where the next value goes: the root, the open array's end, or the key just read.
    json* place(json&& v) {
        if (open_.empty()) {
            root.root = std::move(v);  // replaces a null: nothing to free
            return &root.root;
        }
        json& top = *open_.back();
        if (top.is_array()) {
            auto& a = top.get_ref<json::array_t&>();
            a.push_back(std::move(v));
            return &a.back();
        }
        *slot_ = std::move(v);  // the null the key inserted
        return slot_;
    }
    template <class T>
    bool add(T&& v) {
        place(json(std::forward<T>(v)));
        return true;
    }
    bool open(json&& container) {
        open_.reserve(open_.size() + 1);  // no allocation left between place() and push_back
        open_.push_back(place(std::move(container)));
        return true;
    }
    bool close() {
        open_.pop_back();
        return true;
    }

    // The containers being filled, outermost first; a pointer into its parent stays valid
    // while it is open, because its parent grows only after it closes.
    std::vector<json*> open_;
    json* slot_ = nullptr;
};

}  // namespace

void release(json& j) noexcept {
    if (j.is_array()) {
        auto& a = j.get_ref<json::array_t&>();
        for (json& e : a) release(e);
        a.clear();  // each element now a scalar or an empty container: no allocation
    } else if (j.is_object()) {
        auto& o = j.get_ref<json::object_t&>();
        for (auto& kv : o) release(kv.second);
        o.clear();
    }
}

Document parse(const std::string& text, const std::string& file) {
    // Deeply nested input is refused before parsing: nothing downstream (reading, error
    // messages, freeing) then needs more than kMaxNesting levels of anything.
    size_t at_line = 1, at_col = 0;
    int depth = 0;
    bool in_string = false, escaped = false;
    for (char c : text) {
        if (c == '\n') {
            ++at_line;
            at_col = 0;
        } else {
            ++at_col;
        }
        if (in_string) {
            if (escaped)
                escaped = false;
            else if (c == '\\')
                escaped = true;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > kMaxNesting)
                throw SceneError(file + ":" + std::to_string(at_line) + ":" +
                                 std::to_string(at_col) + ": nested deeper than " +
                                 std::to_string(kMaxNesting) + " levels (the limit)");
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    try {
        TreeBuilder builder;
        json::sax_parse(text, &builder);
        return std::move(builder.root);
    } catch (const std::bad_alloc&) {
        // The partial tree is freed by now: there is memory for the message.
        throw SceneError(file + ": out of memory parsing its " +
                         std::to_string((text.size() + (1 << 20) - 1) >> 20) + " MiB of JSON");
    } catch (const json::parse_error& e) {
        // The byte offset (1-based) as line:column, for editors.
        std::string what = e.what();
        auto pos = what.find(": ", what.find("parse error"));
        std::string detail = pos == std::string::npos ? what : what.substr(pos + 2);
        throw SceneError(file + line_column(text, e.byte > 0 ? e.byte - 1 : 0) +
                         ": invalid JSON: " + detail);
    } catch (const json::exception& e) {
        // E.g. a number too large for a double ("number overflow parsing '1e999'"): nlohmann
        // gives no position here, so the literal it quotes is looked for in the text.
        std::string what = e.what();
        auto pos = what.find("] ");
        const std::string detail = pos == std::string::npos ? what : what.substr(pos + 2);
        std::string place;
        const size_t open = detail.find('\''), close = detail.rfind('\'');
        if (open != std::string::npos && close > open + 1) {
            const size_t at = text.find(detail.substr(open + 1, close - open - 1));
            if (at != std::string::npos) place = line_column(text, at);
        }
        throw SceneError(file + place + ": invalid JSON: " + detail);
    }
}

}  // namespace wavetrace::json_reader
