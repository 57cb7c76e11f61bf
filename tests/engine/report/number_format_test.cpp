// engine/report/number_format: how every number becomes text.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include <kinema/engine/report/number_format.hpp>

using kinema::format_fixed;
using kinema::format_round_trip;
using kinema::format_significant;

TEST_CASE("engine/report/number_format: format_significant") {
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

TEST_CASE("engine/report/number_format: format_round_trip reads back the same double") {
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

TEST_CASE("engine/report/number_format: format_fixed") {
  CHECK(format_fixed(0.12990381056766578) == "0.129904");
  CHECK(format_fixed(2.5, 2) == "2.50");
  CHECK(format_fixed(-12.3456, 1) == "-12.3");
  CHECK(format_fixed(1234567.0, 0) == "1234567");
  CHECK(format_fixed(1e-9, 6) == "0.000000");
  // Large values are printed in full, not cut (the buffer holds them).
  CHECK(format_fixed(1e100, 2).size() == 101 + 3);
}
