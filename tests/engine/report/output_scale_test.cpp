// engine/report/output_scale: SI to the output units the file asks for, the
// same for every printer; angles in degrees wrapped to (-180, 180].
#include <doctest/doctest.h>

#include <cmath>

#include <kinema/engine/report/output_scale.hpp>
#include "../unit_support.hpp"
#include "../../test_support.hpp"

using kinema::Dimension;
using kinema::OutputScale;

namespace {

OutputScale scale_of(const std::string& text) { return OutputScale(kinema_unit::system_from_text(text)); }

}  // namespace

TEST_CASE("engine/report/output_scale: angles in degrees, wrapped to (-180, 180 deg)") {
  const OutputScale scale = scale_of(kinema_test::four_bar_text() + "[output]\nlength = \"mm\"\n");
  const auto deg = [&](double degrees) { return scale.coordinate(Dimension::angle, degrees * M_PI / 180.0); };
  CHECK(deg(40) == doctest::Approx(40).epsilon(1e-14));
  CHECK(deg(190) == doctest::Approx(-170).epsilon(1e-14));
  CHECK(deg(-190) == doctest::Approx(170).epsilon(1e-14));
  CHECK(deg(725) == doctest::Approx(5).epsilon(1e-13));
  CHECK(deg(-359) == doctest::Approx(1).epsilon(1e-12));
  CHECK(std::fabs(deg(360)) < 1e-12);
  // The ends of the interval: +180 stays, -180 becomes +180, and so do odd half turns.
  CHECK(scale.coordinate(Dimension::angle, M_PI) == doctest::Approx(180).epsilon(1e-14));
  CHECK(scale.coordinate(Dimension::angle, -M_PI) == doctest::Approx(180).epsilon(1e-14));
  CHECK(scale.coordinate(Dimension::angle, 3 * M_PI) == doctest::Approx(180).epsilon(1e-14));
  CHECK(scale.coordinate(Dimension::angle, -3 * M_PI) == doctest::Approx(180).epsilon(1e-14));
  for (double radians = -20.0; radians <= 20.0; radians += 0.37) {
    const double wrapped = scale.coordinate(Dimension::angle, radians);
    CAPTURE(radians);
    CHECK(wrapped > -180.0);
    CHECK(wrapped <= 180.0);
    // Same direction as the angle itself.
    CHECK(std::cos(wrapped * M_PI / 180.0) == doctest::Approx(std::cos(radians)).epsilon(1e-12));
    CHECK(std::sin(wrapped * M_PI / 180.0) == doctest::Approx(std::sin(radians)).epsilon(1e-12));
  }
  // Unwrapped: continuous (inputs, curves).
  CHECK(scale.unwrapped(Dimension::angle, 3 * M_PI) == doctest::Approx(540).epsilon(1e-14));
  CHECK(scale.input(-7 * M_PI / 2) == doctest::Approx(-630).epsilon(1e-14));
  CHECK(scale.input_dimension == Dimension::angle);
  // Angular rates stay in rad/s (and rad/s^2).
  CHECK(scale.rate(Dimension::angle, 2.5) == 2.5);
  CHECK(scale.coordinate_unit(Dimension::angle) == "deg");
  CHECK(scale.rate_unit(Dimension::angle) == "rad/s");
  CHECK(scale.second_rate_unit(Dimension::angle) == "rad/s^2");
}

TEST_CASE("engine/report/output_scale: lengths in the file's unit, velocities per second") {
  const OutputScale mm = scale_of(kinema_test::four_bar_text() + "[output]\nlength = \"mm\"\n");
  CHECK(mm.length == doctest::Approx(0.001).epsilon(1e-15));
  CHECK(mm.length_unit == "mm");
  CHECK(mm.coordinate(Dimension::length, 0.05) == doctest::Approx(50).epsilon(1e-14));
  CHECK(mm.coordinate(Dimension::length, -0.5) == doctest::Approx(-500).epsilon(1e-14));  // lengths are not wrapped
  CHECK(mm.unwrapped(Dimension::length, 0.05) == doctest::Approx(50).epsilon(1e-14));
  CHECK(mm.rate(Dimension::length, 0.5) == doctest::Approx(500).epsilon(1e-14));
  CHECK(mm.coordinate_unit(Dimension::length) == "mm");
  CHECK(mm.rate_unit(Dimension::length) == "mm/s");
  CHECK(mm.second_rate_unit(Dimension::length) == "mm/s^2");

  const OutputScale inches = scale_of(kinema_test::four_bar_text() + "[output]\nlength = \"in\"\n");
  CHECK(inches.coordinate(Dimension::length, 0.0254) == doctest::Approx(1).epsilon(1e-14));
  CHECK(inches.rate_unit(Dimension::length) == "in/s");

  // No [output]: metres.
  const OutputScale metres = scale_of(kinema_test::four_bar_text());
  CHECK(metres.length == 1.0);
  CHECK(metres.coordinate(Dimension::length, 0.05) == 0.05);
  CHECK(metres.rate_unit(Dimension::length) == "m/s");

  // A slider input is a length: its values are not wrapped, in the output unit.
  const OutputScale piston(
      kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("piston_driven_crank.toml"))));
  CHECK(piston.input_dimension == Dimension::length);
  CHECK(piston.input(0.17) == doctest::Approx(170).epsilon(1e-14));
  CHECK(piston.coordinate_unit(piston.input_dimension) == "mm");
}
