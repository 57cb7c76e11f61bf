#include "engine/base/toml_ascii.hpp"

#include <algorithm>
#include <cstdio>

#include "engine/base/errors.hpp"
#include "engine/base/user_text.hpp"

namespace kinema {
namespace {

class AsciiRewriter {
 public:
  AsciiRewriter(const std::string& text, const std::string& file) : text_(text), file_(file) {}

  std::string rewrite() {
    out_.reserve(text_.size() + text_.size() / 4);
    // A byte-order mark, which some editors put first: UTF-8 needs none; skipped.
    if (starts_with("\xEF\xBB\xBF")) i_ = 3;
    while (i_ < text_.size()) {
      const char c = text_[i_];
      if (c == '#') {
        comment();
      } else if (starts_with("\"\"\"")) {
        multi_line_basic();
      } else if (c == '"') {
        basic();
      } else if (starts_with("'''")) {
        multi_line_literal();
      } else if (c == '\'') {
        literal();
      } else if (is_ascii(c)) {
        copy();
      } else {
        fail("the character " + code_point_name(code_point()) + " is outside a string or a comment; names and "
             "numbers are ASCII (write it inside \"...\")");
      }
    }
    return out_;
  }

 private:
  const std::string& text_;
  const std::string& file_;
  std::string out_;
  std::size_t i_ = 0;
  int line_ = 1;

  static bool is_ascii(char c) { return static_cast<unsigned char>(c) < 0x80; }
  bool starts_with(const char* s) const { return text_.compare(i_, std::char_traits<char>::length(s), s) == 0; }
  bool at_end() const { return i_ >= text_.size(); }

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(file_ + ":" + std::to_string(line_) + ": syntax error in the mechanism file: " + why);
  }

  // TOML's escapes have exactly 4 or 8 digits.
  static std::string hex(unsigned long value, int digits) {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "%0*lX", digits, value);
    return buffer;
  }

  void copy() {
    if (text_[i_] == '\n') ++line_;
    out_ += text_[i_++];
  }

  // The code point at i_ (UTF-8, checked strictly: no overlong forms, no surrogates), advancing past it.
  unsigned long code_point() {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text_[k]); };
    const unsigned char lead = byte(i_);
    int length = 0;
    unsigned long value = 0;
    unsigned char low = 0x80, high = 0xBF;  // range of the second byte
    if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
      value = lead & 0x1F;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      value = lead & 0x0F;
      if (lead == 0xE0) low = 0xA0;
      if (lead == 0xED) high = 0x9F;
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      value = lead & 0x07;
      if (lead == 0xF0) low = 0x90;
      if (lead == 0xF4) high = 0x8F;
    } else {
      fail("the bytes are not UTF-8 (save the file as UTF-8)");
    }
    if (i_ + length > text_.size()) fail("the bytes are not UTF-8 (save the file as UTF-8)");
    for (int k = 1; k < length; ++k) {
      const unsigned char b = byte(i_ + k);
      if (b < (k == 1 ? low : 0x80) || b > (k == 1 ? high : 0xBF)) fail("the bytes are not UTF-8 (save the file as UTF-8)");
      value = (value << 6) | (b & 0x3F);
    }
    i_ += length;
    return value;
  }

  void escaped_code_point() {
    const unsigned long value = code_point();
    out_ += value > 0xFFFF ? "\\U" + hex(value, 8) : "\\u" + hex(value, 4);
  }

  void comment() {
    while (!at_end() && text_[i_] != '\n') {
      if (is_ascii(text_[i_])) {
        copy();
      } else {
        code_point();
        out_ += '?';
      }
    }
  }

  // "..." and """...""": escapes stay as written, characters past ASCII become escapes.
  void basic() {
    copy();  // "
    while (!at_end() && text_[i_] != '"' && text_[i_] != '\n') basic_character();
    if (!at_end() && text_[i_] == '"') copy();
  }

  void multi_line_basic() {
    out_ += "\"\"\"";
    i_ += 3;
    while (!at_end()) {
      if (starts_with("\"\"\"")) {
        while (!at_end() && text_[i_] == '"') copy();  // up to two quotes may end the content
        return;
      }
      basic_character();
    }
  }

  void basic_character() {
    if (text_[i_] == '\\') {
      copy();
      // An escape of a non-ASCII character is invalid: keep it invalid (toml++ says so).
      if (!at_end()) is_ascii(text_[i_]) ? copy() : (code_point(), void(out_ += '?'));
    } else if (is_ascii(text_[i_])) {
      copy();
    } else {
      escaped_code_point();
    }
  }

  // '...' and '''...''' become the equivalent basic strings (literal strings have no escapes).
  void literal() {
    ++i_;
    out_ += '"';
    while (!at_end() && text_[i_] != '\'' && text_[i_] != '\n') literal_character();
    if (!at_end() && text_[i_] == '\'') {
      ++i_;
      out_ += '"';
    }
  }

  void multi_line_literal() {
    i_ += 3;
    out_ += "\"\"\"";
    while (!at_end()) {
      if (starts_with("'''")) {
        std::size_t quotes = 0;
        while (!at_end() && text_[i_] == '\'') ++quotes, ++i_;
        if (quotes > 5) fail("more than five quotes end a multi-line literal string");
        out_ += std::string(quotes - 3, '\'') + "\"\"\"";
        return;
      }
      literal_character();
    }
  }

  void literal_character() {
    const char c = text_[i_];
    if (c == '\\' || c == '"') {
      out_ += '\\';
      out_ += c;
      ++i_;
    } else if (is_ascii(c)) {
      copy();
    } else {
      escaped_code_point();
    }
  }
};

}  // namespace

std::string ascii_toml(const std::string& text, const std::string& file) {
  if (std::all_of(text.begin(), text.end(), [](char c) { return static_cast<unsigned char>(c) < 0x80; })) return text;
  return AsciiRewriter(text, file).rewrite();
}

}  // namespace kinema
