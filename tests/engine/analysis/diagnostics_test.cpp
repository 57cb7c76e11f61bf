// engine/analysis/diagnostics: each Failure kind as a sentence that names the
// input in output units, the loop and its file:line where one is to blame,
// and what to do. Failures both built by hand and from real sweeps.
#include <doctest/doctest.h>

#include "engine/analysis/diagnostics.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::Failure;
using kinema_unit::kDeg;

namespace {

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

const char* const kTwoLoops = R"toml(title = "two loops"
[parameters]
a = "40 mm"
b = "120 mm"
c = "80 mm"
d = "100 mm"
a2 = "100 mm"
b2 = "50 mm"
c2 = "90 mm"
d2 = "60 mm"
[input]
name = "theta2"
rate = "10 rad/s"
[unknowns]
theta3 = "20 deg"
theta4 = "80 deg"
theta5 = "80 deg"
theta6 = "100 deg"
[loops]
ABCD = "a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d"
Rocker = "a2*exp(I*theta2) + b2*exp(I*theta5) - c2*exp(I*theta6) - d2"
[output]
length = "mm"
)toml";

}  // namespace

TEST_CASE("engine/analysis/diagnostics: describe_input in output units") {
  const auto four_bar = kinema_unit::system_from_text(kinema_test::four_bar_text(), "fb.toml");
  CHECK(kinema::describe_input(four_bar, 40 * kDeg) == "theta2 = 40 deg");
  CHECK(kinema::describe_input(four_bar, 400 * kDeg) == "theta2 = 400 deg");  // an input is not wrapped
  const auto piston =
      kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("piston_driven_crank.toml")), "pdc.toml");
  CHECK(kinema::describe_input(piston, 0.17) == "x = 170 mm");
}

TEST_CASE("engine/analysis/diagnostics: every kind of failure in words") {
  const auto system = kinema_unit::system_from_text(kTwoLoops, "two.toml");
  const double at = 180 * kDeg;

  CHECK(kinema::describe_failure(system, at, Failure{}).empty());

  Failure open;
  open.kind = Failure::Kind::group_open;
  open.group = 1;
  open.residual = 0.0125;  // m
  std::string text = kinema::describe_failure(system, at, open);
  CAPTURE(text);
  CHECK(has(text, "loop \"Rocker\" (two.toml:21)"));  // the loop and where it is written
  CHECK_FALSE(has(text, "ABCD"));
  CHECK(has(text, "theta2 = 180 deg"));
  CHECK(has(text, "12.5 mm"));  // the gap in the output unit
  CHECK(has(text, "from the guesses"));
  CHECK(has(text, "choose another input value"));
  open.group = 0;
  open.from_guesses = false;
  text = kinema::describe_failure(system, at, open);
  CHECK(has(text, "loop \"ABCD\" (two.toml:20)"));
  CHECK(has(text, "last assembled position"));

  Failure stops;
  stops.kind = Failure::Kind::branch_stops;
  stops.from = 90 * kDeg;
  stops.stopped_at = 120 * kDeg;
  text = kinema::describe_failure(system, at, stops);
  CHECK(has(text, "theta2 = 180 deg cannot be reached from theta2 = 90 deg"));
  CHECK(has(text, "near theta2 = 120 deg"));
  CHECK(has(text, "limit or toggle"));

  Failure singular;
  singular.kind = Failure::Kind::singular_jacobian;
  text = kinema::describe_failure(system, 120 * kDeg, singular);
  CHECK(has(text, "singular position at theta2 = 120 deg"));
  CHECK(has(text, "toggle or dead-centre"));
  CHECK(has(text, "choose a nearby value"));

  Failure nonfinite;
  nonfinite.kind = Failure::Kind::nonfinite_rates;
  text = kinema::describe_failure(system, 30 * kDeg, nonfinite);
  CHECK(has(text, "theta2 = 30 deg"));
  CHECK(has(text, "divides by zero"));
  CHECK(has(text, "choose a nearby value"));

  Failure resumed;
  resumed.kind = Failure::Kind::resumed_after_gap;
  text = kinema::describe_failure(system, at, resumed);
  CHECK(has(text, "resumed"));
  CHECK(has(text, "branch"));
}

TEST_CASE("engine/analysis/diagnostics: failures of real runs, in the output units of the file") {
  const kinema::Model model = kinema_unit::model_from_text(kTwoLoops, "two.toml");
  const auto table = kinema::solve_motion(model, {90 * kDeg, 180 * kDeg});
  REQUIRE(table.status(1) == kinema::Status::unassembled);
  const std::string stops = kinema::describe_failure(model.system, table[1]);
  CAPTURE(stops);
  CHECK(has(stops, "theta2 = 180 deg cannot be reached from theta2 = 90 deg"));

  const auto fresh = kinema::solve_motion(model, {180 * kDeg});
  const std::string open = kinema::describe_failure(model.system, fresh[0]);
  CAPTURE(open);
  CHECK(has(open, "loop \"Rocker\" (two.toml:21) cannot be closed at theta2 = 180 deg"));
  CHECK(has(open, " mm after Newton-Raphson"));

  // The piston's dead centre, in mm.
  const kinema::Model piston = kinema::load_model(kinema_test::sample("piston_driven_crank.toml"));
  kinema::Workspace workspace(piston);
  const auto dead = workspace.motion(0.2, -2.0, 5.0, Eigen::VectorXd::Zero(2));
  CHECK(kinema::describe_failure(piston.system, dead).find("singular position at x = 200 mm") == 0);
}
