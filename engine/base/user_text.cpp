#include "engine/base/user_text.hpp"

#include <cstdio>

namespace kinema {

unsigned long next_code_point(const std::string& text, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  if (lead < 0x80) return lead;
  const int length = lead >= 0xF0 && lead <= 0xF4 ? 4 : lead >= 0xE0 ? (lead <= 0xEF ? 3 : 0) : lead >= 0xC2 ? 2 : 0;
  if (length == 0 || i + length > text.size()) return 0xFFFD;
  unsigned long value = lead & (0x7F >> length);
  for (int k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0xFFFD;
    value = (value << 6) | (byte(i + k) & 0x3F);
  }
  i += length - 1;
  return value;
}

bool is_control_character(unsigned long c) {
  return c < 0x20 || (c >= 0x7F && c <= 0x9F) || c == 0x2028 || c == 0x2029;
}

bool is_bidi_control(unsigned long c) {
  return c == 0x061C || c == 0x200E || c == 0x200F || (c >= 0x202A && c <= 0x202E) || (c >= 0x2066 && c <= 0x2069);
}

std::string code_point_name(unsigned long c) {
  char name[16];
  std::snprintf(name, sizeof name, "U+%04lX", c);
  return name;
}

std::string one_line(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const std::size_t start = i;
    const unsigned long c = next_code_point(text, i);
    if (is_control_character(c)) out += ' ';
    else if (is_bidi_control(c) || c == 0xFFFD) out += "[" + code_point_name(c) + "]";
    else out.append(text, start, i + 1 - start);
  }
  return out;
}

std::string terminal_text(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const std::size_t start = i;
    const unsigned long c = next_code_point(text, i);
    if (c == '\n') out += '\n';
    else if (is_control_character(c) || is_bidi_control(c) || c == 0xFFFD) out += "[" + code_point_name(c) + "]";
    else out.append(text, start, i + 1 - start);
  }
  return out;
}

}  // namespace kinema
