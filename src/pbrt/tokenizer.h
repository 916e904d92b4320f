// The tokens of a pbrt-v4 scene file, as pbrt's own tokenizer splits them: quoted strings,
// brackets, and words (directive names, numbers, true/false), with comments (# to the end of
// the line) and white space between them.
#pragma once

#include <string>
#include <string_view>

namespace wavetrace {

struct PbrtToken {
    enum class Kind { String, Word, Open, Close } kind;
    std::string text;  // a string without its quotes, escapes resolved
    int line = 0;
};

class PbrtTokenizer {
  public:
    // `file` names the text in errors ("scene.pbrt:12: ...").
    PbrtTokenizer(std::string text, std::string file);

    // The next token; false at the end of the text. Throws SceneError at an unterminated
    // string, an unknown escape or a NUL byte, naming the file and line.
    bool next(PbrtToken* token);

    // A token handed back: next() returns it again.
    void unget(PbrtToken token);

    const std::string& file() const { return file_; }
    int line() const { return line_; }

  private:
    [[noreturn]] void fail(const std::string& message) const;

    std::string text_;
    std::string file_;
    size_t pos_ = 0;
    int line_ = 1;
    bool has_pending_ = false;
    PbrtToken pending_;
};

}  // namespace wavetrace
