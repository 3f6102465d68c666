// io/text_reader.hpp - a whitespace tokenizer over an in-memory text file that knows its line
// number, for the OFF reader and the body of ASCII PLY files (private to jade_io).
//
// Errors read "<file>: line <n>: <what>", naming the line of the last token read, so a user can
// open the file at the right place.
#pragma once

#include "io/common.hpp"

#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

namespace jade::io {

class TextReader {
public:
    /// `first_line` is the line number of text[0] (PLY bodies start after the header).
    TextReader(std::string_view file, std::string_view text, size_t first_line = 1, bool hash_comments = true)
        : file_(file), text_(text), line_(first_line), token_line_(first_line), hash_comments_(hash_comments)
    {
    }

    /// The next token, or an empty view at the end of the file.
    std::string_view next()
    {
        skip_space();
        token_line_ = line_;
        const size_t begin = pos_;
        while (pos_ < text_.size() && !is_space(text_[pos_]) && !(hash_comments_ && text_[pos_] == '#')) ++pos_;
        return text_.substr(begin, pos_ - begin);
    }

    /// The next token without consuming it.
    std::string_view peek()
    {
        const size_t pos = pos_, line = line_, token_line = token_line_;
        auto t = next();
        pos_ = pos;
        line_ = line;
        token_line_ = token_line;
        return t;
    }

    /// What a value is, for messages: "vertex count", or "coordinate of vertex" + element 12.
    /// The text is only put together when a message needs it (this runs once per value).
    struct What {
        static constexpr uint64_t kNoElement = ~uint64_t(0);
        What(const char* text_, uint64_t element_ = kNoElement) : text(text_), element(element_) {}
        What(std::string_view text_, uint64_t element_) : text(text_), element(element_) {}
        std::string_view text;
        uint64_t element;
        std::string str() const
        {
            return element == kNoElement ? std::string(text) : std::string(text) + " " + std::to_string(element);
        }
    };

    /// The next token; `what` names the expected value in the end-of-file message.
    std::string_view token(What what)
    {
        auto t = next();
        if (t.empty()) fail("unexpected end of file (expected " + what.str() + ")");
        return t;
    }

    double real(What what)
    {
        auto t = token(what);
        if (t.size() > 1 && t[0] == '+' && t[1] != '-') t.remove_prefix(1);  // from_chars rejects '+'
        double v = 0.0;
        auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        // Out-of-range values (1e999) are a parse error here rather than a silent infinity.
        if (ec != std::errc() || end != t.data() + t.size()) bad_token(what, t);
        return v;
    }

    uint64_t count(What what) { return parse_integer<uint64_t>(what); }
    int64_t integer(What what) { return parse_integer<int64_t>(what); }

    /// Skips the rest of the current line (the remaining values of a vertex or face line that
    /// the reader does not use, e.g. colours).
    void skip_line()
    {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
        if (pos_ < text_.size()) {
            ++pos_;
            ++line_;
        }
    }

    /// True when only whitespace and comments remain.
    bool at_end()
    {
        skip_space();
        return pos_ >= text_.size();
    }

    size_t line() const { return token_line_; }
    size_t bytes_left() const { return text_.size() - pos_; }

    [[noreturn]] void fail(const std::string& what) const
    {
        io::fail(file_, "line " + std::to_string(token_line_) + ": " + what);
    }

private:
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

    void skip_space()
    {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == '\n') {
                ++line_;
                ++pos_;
            } else if (is_space(c)) {
                ++pos_;
            } else if (hash_comments_ && c == '#') {
                while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
            } else {
                return;
            }
        }
    }

    template <class T> T parse_integer(What what)
    {
        auto t = token(what);
        if (t.size() > 1 && t[0] == '+' && t[1] != '-') t.remove_prefix(1);
        T v = 0;
        auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
        if (ec != std::errc() || end != t.data() + t.size()) bad_token(what, t);
        return v;
    }

    [[noreturn]] void bad_token(What what, std::string_view t) const
    {
        fail("expected " + what.str() + ", got '" + printable(t) + "'");
    }

    std::string_view file_;
    std::string_view text_;
    size_t pos_ = 0;
    size_t line_;
    size_t token_line_;
    bool hash_comments_;
};

}  // namespace jade::io
