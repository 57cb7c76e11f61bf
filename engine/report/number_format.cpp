#include <kinema/engine/report/number_format.hpp>

#include <cstdio>

namespace kinema {

std::string format_significant(double value, int significant) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", significant, value == 0 ? 0.0 : value);  // 0.0: no "-0"
  return buffer;
}

std::string format_round_trip(double value) { return format_significant(value, 17); }

std::string format_fixed(double value, int decimals) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

}  // namespace kinema
