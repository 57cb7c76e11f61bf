#include <kinema/engine/report/number_format.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace kinema {

namespace {

// 10^k for |k| <= kPowers, each correctly rounded (strtod rounds correctly).
constexpr int kPowers = 300;
const std::array<double, 2 * kPowers + 1>& powers_of_ten() {
  static const auto table = [] {
    std::array<double, 2 * kPowers + 1> powers{};
    for (int k = -kPowers; k <= kPowers; ++k) powers[k + kPowers] = std::strtod(("1e" + std::to_string(k)).c_str(), nullptr);
    return powers;
  }();
  return table;
}

constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Exactly 8 decimal digits of value < 10^8, as four independent pairs (no chain of
// dependent divisions: this is the inner loop of a CSV of millions of numbers).
void put_8_digits(char* out, std::uint32_t value) {
  const std::uint32_t high = value / 10000, low = value % 10000;
  std::memcpy(out, kDigitPairs + 2 * (high / 100), 2);
  std::memcpy(out + 2, kDigitPairs + 2 * (high % 100), 2);
  std::memcpy(out + 4, kDigitPairs + 2 * (low / 100), 2);
  std::memcpy(out + 6, kDigitPairs + 2 * (low % 100), 2);
}

// The 16 decimal digits of value < 10^16, leading zeros included.
void put_16_digits(char* out, std::uint64_t value) {
  put_8_digits(out, static_cast<std::uint32_t>(value / 100000000));
  put_8_digits(out + 8, static_cast<std::uint32_t>(value % 100000000));
}

// Copies of 16 bytes whatever the length needed (the buffers have the room): a
// variable-length memcpy is a library call, and this runs three times a number.
void copy_16(char* to, const char* from) { std::memcpy(to, from, 16); }

// A magnitude rounded to `digits` significant digits: mantissa * 10^(exponent - digits + 1),
// 10^(digits-1) <= mantissa < 10^digits.
struct Decimal {
  std::uint64_t mantissa;
  int exponent;
};

// The Decimal of a finite non-zero magnitude with `digits` <= 13 significant digits, or
// false when the scaled value is too close to a rounding tie to decide in double
// arithmetic (the caller then asks std::to_chars, which decides exactly). The scaling
// magnitude * 10^k errs by at most about 2.3e-16 relative, i.e. 10^digits * 2.3e-16 in
// the last digit; the window below is over four times that.
bool to_decimal(double magnitude, int digits, Decimal& decimal) {
  const auto& powers = powers_of_ten();
  if (!(magnitude >= 1e-280 && magnitude <= 1e280)) return false;
  // floor(log10(magnitude)) to within one (corrected below) from the binary exponent:
  // floor(e2 log10 2) = (e2 * 78913) >> 18 for the exponents of normal doubles.
  std::uint64_t bits;
  std::memcpy(&bits, &magnitude, sizeof bits);
  const int binary_exponent = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  int exponent = (binary_exponent * 78913) >> 18;
  const double low = powers[kPowers + digits - 1], high = powers[kPowers + digits];
  double scaled = magnitude * powers[kPowers + digits - 1 - exponent];
  if (scaled < low) scaled = magnitude * powers[kPowers + digits - 1 - --exponent];
  else if (scaled >= high) scaled = magnitude * powers[kPowers + digits - 1 - ++exponent];
  auto mantissa = static_cast<std::uint64_t>(scaled);  // floor: scaled > 0
  const double fraction = scaled - static_cast<double>(mantissa);
  if (std::fabs(fraction - 0.5) < high * 1e-15) return false;
  if (fraction > 0.5) ++mantissa;
  if (mantissa >= static_cast<std::uint64_t>(high)) {  // 9.99...95 rounded up to 10.0...
    mantissa /= 10;
    ++exponent;
  }
  decimal = {mantissa, exponent};
  return true;
}

// %g at out (kMaxNumberChars - 1 bytes free) of the number whose 16 digits (leading
// zeros first) are at all_digits, with 16 more bytes readable after them.
char* put_digits(char* out, const char* all_digits, int exponent, int digits) {
  const char* text = all_digits + 16 - digits;
  int length = digits;
  while (length > 1 && text[length - 1] == '0') --length;  // %g drops trailing zeros
  // out has kMaxNumberChars - 1 bytes (a sign may precede): each copy_16 below stays inside.
  if (exponent < -4 || exponent >= digits) {  // scientific: d.ddd e+XX
    out[0] = text[0];
    if (length > 1) {
      out[1] = '.';
      copy_16(out + 2, text + 1);
      out += length + 1;
    } else {
      out += 1;
    }
    *out++ = 'e';
    *out++ = exponent < 0 ? '-' : '+';
    const int e = std::abs(exponent);
    if (e >= 100) *out++ = static_cast<char>('0' + e / 100);
    std::memcpy(out, kDigitPairs + 2 * (e % 100), 2);
    return out + 2;
  }
  if (exponent >= 0) {  // ddd.ddd
    const int whole_digits = exponent + 1;
    copy_16(out, text);
    if (length <= whole_digits) return out + whole_digits;
    out[whole_digits] = '.';
    copy_16(out + whole_digits + 1, text + whole_digits);
    return out + length + 1;
  }
  out[0] = '0';  // 0.000ddd
  out[1] = '.';
  out[2] = out[3] = out[4] = '0';
  out += 1 - exponent;
  copy_16(out, text);
  return out + length;
}


// %g of a finite non-zero magnitude with `digits` <= 13 significant digits, or nullptr
// near a rounding tie (see to_decimal).
char* put_significant_fast(char* out, double magnitude, int digits) {
  Decimal decimal;
  if (!to_decimal(magnitude, digits, decimal)) return nullptr;
  char all_digits[32];
  put_16_digits(all_digits, decimal.mantissa);
  return put_digits(out, all_digits, decimal.exponent, digits);
}

}  // namespace

// std::to_chars: printf's %.*g digits without its locale and format parsing; for up to
// 13 digits a faster path that gives the same characters (checked against to_chars
// in tests/engine/report/number_format_test.cpp) and defers to it near a tie.
char* put_significant(char* out, double value, int significant) {
  if (value == 0) {  // no "-0"
    *out = '0';
    return out + 1;
  }
  if (significant >= 1 && significant <= 13 && std::isfinite(value)) {
    char* digits = out;
    if (value < 0) *digits++ = '-';
    if (char* end = put_significant_fast(digits, std::fabs(value), significant)) return end;
  }
  return std::to_chars(out, out + kMaxNumberChars, value, std::chars_format::general, significant).ptr;
}

char* put_significant_list(char* out, const double* values, std::size_t count, int significant, char separator) {
  if (!(significant >= 1 && significant <= 13)) {
    for (std::size_t k = 0; k < count; ++k) {
      if (k > 0) *out++ = separator;
      if (!std::isnan(values[k])) out = put_significant(out, values[k], significant);
    }
    return out;
  }
  // Three passes over up to 64 values: each value as a Decimal (the floating-point
  // part), then the digits of each, then each text. Apart, a pass's work overlaps from
  // one value to the next, and the texts read digits stored long before (reading bytes
  // just stored in pieces stalls); one value at a time, the processor waits on each
  // value's chain of steps: 15 ns a value against 20 (Problem 4.4's CSV, this machine).
  enum Kind : unsigned char { kNumber, kZero, kEmpty, kExact };
  constexpr std::size_t kChunk = 64;
  Decimal decimals[kChunk];
  Kind kinds[kChunk];
  char texts[kChunk + 1][16];  // each number's 16 digits; one more row: room to read past the last
  for (std::size_t begin = 0; begin < count; begin += kChunk) {
    const std::size_t n = std::min(kChunk, count - begin);
    for (std::size_t k = 0; k < n; ++k) {
      const double value = values[begin + k];
      decimals[k] = {0, 0};  // the digits pass converts every entry
      if (value == 0) kinds[k] = kZero;
      else if (std::isnan(value)) kinds[k] = kEmpty;
      else if (std::isfinite(value) && to_decimal(std::fabs(value), significant, decimals[k])) kinds[k] = kNumber;
      else kinds[k] = kExact;
    }
    for (std::size_t k = 0; k < n; ++k) put_16_digits(texts[k], decimals[k].mantissa);  // also unused ones: no branch
    for (std::size_t k = 0; k < n; ++k) {
      if (begin + k > 0) *out++ = separator;
      const double value = values[begin + k];
      switch (kinds[k]) {
        case kNumber:
          *out = '-';  // kept for a negative value only
          out = put_digits(out + (value < 0), texts[k], decimals[k].exponent, significant);
          break;
        case kZero:
          *out++ = '0';
          break;
        case kEmpty:
          break;
        case kExact:
          out = std::to_chars(out, out + kMaxNumberChars, value, std::chars_format::general, significant).ptr;
          break;
      }
    }
  }
  return out;
}

char* put_shortest(char* out, double value) {
  return std::to_chars(out, out + kMaxNumberChars, value == 0 ? 0.0 : value).ptr;
}

std::string format_significant(double value, int significant) {
  char buffer[kMaxNumberChars];
  return std::string(buffer, put_significant(buffer, value, significant));
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
