#include "pbrt/tokenizer.h"

#include <utility>

#include "wavetrace/scene/scene.h"

namespace wavetrace {

PbrtTokenizer::PbrtTokenizer(std::string text, std::string file)
    : text_(std::move(text)), file_(std::move(file)) {}

void PbrtTokenizer::fail(const std::string& message) const {
    throw SceneError(file_ + ":" + std::to_string(line_) + ": " + message);
}

void PbrtTokenizer::unget(PbrtToken token) {
    pending_ = std::move(token);
    has_pending_ = true;
}

bool PbrtTokenizer::next(PbrtToken* token) {
    if (has_pending_) {
        *token = std::move(pending_);
        has_pending_ = false;
        return true;
    }
    const size_t n = text_.size();
    for (;;) {
        if (pos_ >= n) return false;
        const char c = text_[pos_];
        if (c == '\n') {
            ++line_;
            ++pos_;
        } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
            ++pos_;
        } else if (c == '#') {
            while (pos_ < n && text_[pos_] != '\n') ++pos_;
        } else if (c == '\0') {
            fail("a NUL byte (is this a text file?)");
        } else {
            break;
        }
    }
    token->line = line_;
    token->text.clear();
    const char c = text_[pos_];
    if (c == '[' || c == ']') {
        token->kind = c == '[' ? PbrtToken::Kind::Open : PbrtToken::Kind::Close;
        token->text = c;
        ++pos_;
        return true;
    }
    if (c == '"') {
        token->kind = PbrtToken::Kind::String;
        ++pos_;
        for (;;) {
            if (pos_ >= n || text_[pos_] == '\n') fail("unterminated string");
            char ch = text_[pos_++];
            if (ch == '"') return true;
            if (ch == '\0') fail("a NUL byte in a string");
            if (ch == '\\') {
                if (pos_ >= n) fail("unterminated string");
                const char e = text_[pos_++];
                switch (e) {
                    case 'b': ch = '\b'; break;
                    case 'f': ch = '\f'; break;
                    case 'n': ch = '\n'; break;
                    case 'r': ch = '\r'; break;
                    case 't': ch = '\t'; break;
                    case '\\': ch = '\\'; break;
                    case '\'': ch = '\''; break;
                    case '"': ch = '"'; break;
                    default: fail(std::string("unknown escape \\") + e + " in a string");
                }
            }
            token->text += ch;
        }
    }
    token->kind = PbrtToken::Kind::Word;
    while (pos_ < n) {
        const char ch = text_[pos_];
        if (ch == ' ' || ch == '\n' || ch == '\t' || ch == '\r' || ch == '\f' || ch == '\v' ||
            ch == '"' || ch == '[' || ch == ']' || ch == '#')
            break;
        if (ch == '\0') fail("a NUL byte (is this a text file?)");
        token->text += ch;
        ++pos_;
    }
    return true;
}

}  // namespace wavetrace
