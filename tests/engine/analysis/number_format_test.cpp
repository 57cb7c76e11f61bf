// engine/base/number_format: how every number becomes text.
#include <doctest/doctest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "engine/base/number_format.hpp"

using kinema::format_fixed;
using kinema::format_round_trip;
using kinema::format_significant;

TEST_CASE("engine/base/number_format: format_significant") {
  CHECK(format_significant(0.12990381056766578) == "0.129904");
  CHECK(format_significant(-60.190312) == "-60.1903");
  CHECK(format_significant(6.283185307179586) == "6.28319");
  CHECK(format_significant(1e-5) == "1e-05");
  CHECK(format_significant(123456789.0) == "1.23457e+08");
  CHECK(format_significant(2.0) == "2");
  CHECK(format_significant(3.14159265, 3) == "3.14");
  CHECK(format_significant(0.000123456, 2) == "0.00012");
  CHECK(format_significant(1.0 / 3.0, 12) == "0.333333333333");
  // Never "-0" (a value that is zero prints as zero whatever its sign) ...
  CHECK(format_significant(-0.0) == "0");
  CHECK(format_significant(0.0) == "0");
  // ... but a small negative number keeps its sign.
  CHECK(format_significant(-1e-20) == "-1e-20");
  CHECK(format_significant(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(format_significant(std::nan("")).find("nan") != std::string::npos);
}

TEST_CASE("engine/base/number_format: zero at the scale a value is shown at") {
  // Below 1e-12 of the scale, round-off: 0; from there on, the value, its sign kept.
  CHECK(kinema::zero_at_scale(1.00804e-16, 1.64625) == 0);
  CHECK(kinema::zero_at_scale(-9.9e-13, 1.0) == 0);
  CHECK(kinema::zero_at_scale(-1e-12, 1.0) == -1e-12);
  CHECK(kinema::zero_at_scale(3e-9, 1000.0) == 3e-9);
  CHECK(kinema::zero_at_scale(1e-300, 0.0) == 1e-300);  // no scale known: nothing is zeroed
  CHECK(std::isnan(kinema::zero_at_scale(std::nan(""), 1.0)));
  CHECK(kinema::format_at_scale(1.00804e-16, 1.64625) == "0");
  CHECK(kinema::format_at_scale(-2.01615e-16, 3.29262) == "0");
  CHECK(kinema::format_at_scale(1.64625, 1.64625) == "1.64625");
  CHECK(kinema::format_at_scale(0.000123456, 1.0, 2) == "0.00012");
  // A column's scale: its largest finite magnitude (an undefined value counts for nothing).
  const double column[] = {0.5, -7.25, std::nan(""), 3.0};
  CHECK(kinema::largest_magnitude(column, 4) == 7.25);
  CHECK(kinema::largest_magnitude({std::numeric_limits<double>::infinity(), -2.0}) == 2.0);
  CHECK(kinema::largest_magnitude(column, 0) == 0);
}

TEST_CASE("engine/base/number_format: format_round_trip reads back the same double") {
  for (double value : {0.1, 1.0 / 3.0, M_PI, -2.5e17, 1e-300, 4.9e-324, 0.30000000000000004, 123.456,
                       std::numeric_limits<double>::max()}) {
    CAPTURE(value);
    const std::string text = format_round_trip(value);
    CHECK(std::strtod(text.c_str(), nullptr) == value);
  }
  CHECK(format_round_trip(0.5) == "0.5");
  CHECK(format_round_trip(-0.0) == "0");
  // 17 digits where they are needed: 0.1 is not exactly 0.1.
  CHECK(format_round_trip(0.1) == "0.10000000000000001");
}

TEST_CASE("engine/base/number_format: format_fixed") {
  CHECK(format_fixed(0.12990381056766578) == "0.129904");
  CHECK(format_fixed(2.5, 2) == "2.50");
  CHECK(format_fixed(-12.3456, 1) == "-12.3");
  CHECK(format_fixed(1234567.0, 0) == "1234567");
  CHECK(format_fixed(1e-9, 6) == "0.000000");
  CHECK(format_fixed(-1e-9, 3) == "0.000");  // not "-0.000"
  CHECK(format_fixed(-0.0, 2) == "0.00");
  CHECK(format_fixed(-0.0004, 3) == "0.000");
  CHECK(format_fixed(-0.0006, 3) == "-0.001");
  // Large values are printed in full, not cut (the buffer holds them).
  CHECK(format_fixed(1e100, 2).size() == 101 + 3);
}

// put_significant has its own path for up to 13 digits; it must give exactly what
// std::to_chars (%g, correctly rounded) gives, including next to rounding ties,
// powers of ten and values that round up into the next decade.
TEST_CASE("engine/base/number_format: put_significant equals std::to_chars for every kind of double") {
  std::mt19937_64 random(20261122);
  std::uniform_int_distribution<int> decade(-300, 300);
  long mismatches = 0, checked = 0;
  auto check = [&](double value, int digits) {
    char fast[kinema::kMaxNumberChars], exact[64];
    const std::string a(fast, kinema::put_significant(fast, value, digits));
    const std::string b(exact, std::to_chars(exact, exact + sizeof exact, value == 0 ? 0.0 : value,
                                             std::chars_format::general, digits).ptr);
    ++checked;
    if (a != b && ++mismatches <= 5) {
      CAPTURE(value);
      CAPTURE(digits);
      CHECK(a == b);
    }
  };
  for (int i = 0; i < 200000; ++i) {
    std::uint64_t bits = random();
    double any;
    std::memcpy(&any, &bits, sizeof any);
    if (std::isfinite(any))
      for (int digits : {1, 6, 12, 13}) check(any, digits);
    const double power = std::pow(10.0, decade(random) / 3);
    check(power, 12);
    check(std::nextafter(power, 0.0), 12);
    check(std::nextafter(power, 1e300), 6);
    const double tie = static_cast<double>(random() % 1000000000000ULL) + 0.5;  // exact ties at 12 digits
    check(tie, 12);
    check(tie / 1e6, 12);
    check(-tie * 1e-9, 12);
    check(std::ldexp(static_cast<double>(random() >> 11), decade(random)), 12);
  }
  for (double value : {0.5, 1.5, 2.5, 9.5, 99.5, 999999.5, 9999995.0, 1e-5, 123456789012.5, 1e22, 9.9999999999995,
                       -0.0, 1e300, 5e-324, 2.2250738585072014e-308})
    for (int digits = 1; digits <= 17; ++digits) check(value, digits);
  CHECK(mismatches == 0);
  CHECK(checked > 1000000);
}

TEST_CASE("engine/base/number_format: put_significant_list writes what put_significant writes, NaN empty") {
  std::mt19937_64 random(20261123);
  std::uniform_int_distribution<int> decade(-300, 300);
  std::vector<double> values;
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t bits = random();
    double any;
    std::memcpy(&any, &bits, sizeof any);  // every kind: NaN, infinities, subnormals too
    values.push_back(any);
    values.push_back(std::ldexp(static_cast<double>(random() >> 11), decade(random) / 10));
    values.push_back(static_cast<double>(random() % 1000000000000ULL) + 0.5);  // ties at 12 digits
    if (i % 7 == 0) values.push_back(i % 2 ? 0.0 : -0.0);
    if (i % 11 == 0) values.push_back(std::numeric_limits<double>::quiet_NaN());
    // Plain notation ("0.000ddd" to "ddddddddddddd"), each exponent with as many trailing
    // zeros as digits after them: a mechanism's results, and every shuffle pattern.
    const double whole = static_cast<double>(random() % 10000000000000ULL) / std::pow(10.0, random() % 13);
    values.push_back((i % 2 ? -1 : 1) * whole * std::pow(10.0, static_cast<int>(random() % 18) - 6));
  }
  // The list in chunks without vector instructions (what other processors run); past 13
  // digits there is no chunked path.
  const auto portable_list = [](char* out, const double* list, std::size_t count, int digits) {
    if (!kinema::SignificantChunk::handles(digits)) return kinema::put_significant_list(out, list, count, digits, ';');
    kinema::SignificantChunk chunk;
    for (std::size_t begin = 0; begin < count; begin += chunk.capacity) {
      const std::size_t n = std::min(chunk.capacity, count - begin);
      chunk.convert(list + begin, n, digits, false);
      if (begin > 0) *out++ = ';';
      out = chunk.put(out, 0, n, ';');
    }
    return out;
  };
  std::size_t lists = 0, characters = 0;
  for (int digits : {1, 6, 8, 9, 12, 13, 15, 17}) {
    // Lists of every length up to past two chunks of 64, from anywhere in the values.
    for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(3), std::size_t(63), std::size_t(64),
                              std::size_t(65), std::size_t(130), values.size()}) {
      for (std::size_t first = 0; first + count <= values.size(); first += count > 1000 ? values.size() : 977) {
        std::string expected;
        char one[kinema::kMaxNumberChars];
        for (std::size_t k = 0; k < count; ++k) {
          if (k > 0) expected += ';';
          if (!std::isnan(values[first + k])) expected.append(one, kinema::put_significant(one, values[first + k], digits));
        }
        std::vector<char> buffer((kinema::kMaxNumberChars + 1) * count + 1);
        char* end = kinema::put_significant_list(buffer.data(), values.data() + first, count, digits, ';');
        const std::string got(buffer.data(), end);
        end = portable_list(buffer.data(), values.data() + first, count, digits);
        const std::string portable(buffer.data(), end);
        ++lists;
        characters += got.size();
        if (got != expected || portable != expected) {
          CAPTURE(digits);
          CAPTURE(count);
          CAPTURE(first);
          REQUIRE(got == expected);
          REQUIRE(portable == expected);
        }
      }
    }
  }
  CHECK(lists > 500);
  CHECK(characters > 1000000);
  MESSAGE("put_significant_list with vector instructions: " << std::string(kinema::vector_number_path() ? "yes" : "no"));
}

TEST_CASE("engine/base/number_format: put_shortest reads back as the same double") {
  char text[kinema::kMaxNumberChars];
  for (double value : {0.1, 6.283185307179586, 1e-5, -2.5e300, 0.0684484038671}) {
    const std::string printed(text, kinema::put_shortest(text, value));
    CHECK(std::strtod(printed.c_str(), nullptr) == value);
  }
  CHECK(std::string(text, kinema::put_shortest(text, -0.0)) == "0");
  CHECK(std::string(text, kinema::put_shortest(text, 0.1)) == "0.1");
}
