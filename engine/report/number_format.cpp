#include <kinema/engine/report/number_format.hpp>

#include <charconv>
#include <cstdio>

namespace kinema {

// std::to_chars: printf's %.*g digits without its locale and format parsing (several
// times faster on the long sweeps that print millions of numbers).
std::string format_significant(double value, int significant) {
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value == 0 ? 0.0 : value,  // 0.0: no "-0"
                                 std::chars_format::general, significant)
                       .ptr;
  return std::string(buffer, end);
}

double round_significant(double value, int significant) {
  char buffer[64];
  const auto end =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, significant).ptr;
  double rounded = value;
  std::from_chars(buffer, end, rounded);
  return rounded;
}

std::string format_round_trip(double value) { return format_significant(value, 17); }

std::string format_fixed(double value, int decimals) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

}  // namespace kinema
