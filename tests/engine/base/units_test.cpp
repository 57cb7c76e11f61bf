#include <doctest/doctest.h>

#include <cmath>

#include "engine/base/errors.hpp"
#include "readers/mechanism_file.hpp"
#include "engine/base/units.hpp"

using namespace kinema;

TEST_CASE("quantities are converted to SI with their dimension") {
  CHECK(parse_quantity("150 mm").si_value == doctest::Approx(0.15));
  CHECK(parse_quantity("150 mm").dimension == Dimension::length);
  CHECK(parse_quantity("2 in").si_value == doctest::Approx(0.0508));
  CHECK(parse_quantity("0.3 m").si_value == doctest::Approx(0.3));
  CHECK(parse_quantity("34 deg").si_value == doctest::Approx(34 * M_PI / 180));
  CHECK(parse_quantity("34 deg").dimension == Dimension::angle);
  CHECK(parse_quantity("60 rpm").si_value == doctest::Approx(2 * M_PI));
  CHECK(parse_quantity("60 rpm").dimension == Dimension::angular_velocity);
  CHECK(parse_quantity("4.712 rad/s").si_value == doctest::Approx(4.712));
  CHECK(parse_quantity("15 rad/s^2").dimension == Dimension::angular_acceleration);
  CHECK(parse_quantity("22.25 in/s").si_value == doctest::Approx(22.25 * 0.0254));
  CHECK(parse_quantity("22.25 in/s").dimension == Dimension::velocity);
  CHECK(parse_quantity("5 m/s^2").dimension == Dimension::acceleration);
  CHECK(parse_quantity("-42").dimension == Dimension::number);
}

TEST_CASE("unknown units and non-finite numbers are refused with the list of units") {
  CHECK_THROWS_AS(parse_quantity("3 furlongs"), UnitError);
  CHECK_THROWS_WITH_AS(parse_quantity("3 furlongs"), doctest::Contains("mm"), UnitError);
  CHECK_THROWS_AS(parse_quantity("1e999 mm"), UnitError);
  CHECK_THROWS_AS(parse_quantity("mm"), UnitError);
}

// Session 30's review: strtod read --angle 0x10 as 16 deg (and "inf", "nan" as numbers)
// while --sweep 0x0:0x10:0x8 was refused: a number is decimal digits everywhere.
TEST_CASE("a quantity's number is decimal: hexadecimal, inf and nan are refused") {
  CHECK(parse_quantity(".5 deg").si_value == doctest::Approx(0.5 * M_PI / 180));
  CHECK(parse_quantity("-.5e1 deg").si_value == doctest::Approx(-5 * M_PI / 180));
  CHECK(parse_quantity("5.").si_value == 5);
  CHECK(parse_quantity("40deg").si_value == doctest::Approx(40 * M_PI / 180));
  CHECK_THROWS_WITH_AS(parse_quantity("0x10"), doctest::Contains("hexadecimal"), UnitError);
  CHECK_THROWS_WITH_AS(parse_quantity("0x1p4 deg"), doctest::Contains("hexadecimal"), UnitError);
  CHECK_THROWS_WITH_AS(parse_quantity("inf"), doctest::Contains("not a number with a unit"), UnitError);
  CHECK_THROWS_WITH_AS(parse_quantity("nan mm"), doctest::Contains("not a number with a unit"), UnitError);
  CHECK_THROWS_WITH_AS(parse_quantity("1e999 mm"), doctest::Contains("not a finite number"), UnitError);
  CHECK_THROWS_WITH_AS(parse_quantity("1e mm"), doctest::Contains("unit \"e mm\""), UnitError);
}

TEST_CASE("sweeps include the stop value and refuse steps that never reach it") {
  const auto values = parse_sweep("0:360:90", 1.0).to_vector();
  REQUIRE(values.size() == 5);
  CHECK(values.back() == doctest::Approx(360));
  CHECK(parse_sweep("10:0:-5", 1.0).size() == 3);
  CHECK_THROWS_AS(parse_sweep("0:10:-1", 1.0), InputError);
  CHECK_THROWS_AS(parse_sweep("0:10:0", 1.0), InputError);
  CHECK_THROWS_AS(parse_sweep("0-10", 1.0), InputError);
}
