// The web page's slider ranges (engine/analysis/slider_ranges): where the four-bar and the
// slider-crank assemble over a turn, against the limits worked by hand from the link
// lengths (a triangle closes when no side is longer than the other two together), and the
// caps where a parameter does not stop the mechanism assembling.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/analysis/resolving.hpp"
#include "engine/base/units.hpp"
#include "engine/model.hpp"
#include "engine/numeric/sweep.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

namespace {

// The ends are bisected to 1e-7 of the caps' width (5 times the file's value): to 1e-6
// relative for limits of the size of the file's values.
constexpr double kRelative = 1e-6;

struct Solved {
  kinema::Model model;
  kinema::MotionTable rows;
  kinema::Resolving resolving;
};

// A sample, its crank turned in `step_deg` steps from 0 (as the page's --sweep 0:...:STEP
// solves it), and the resolving with the sliders' ranges over those rows.
Solved solved_turn(const std::string& name, double step_deg) {
  Solved s{kinema::make_model(kinema::read_mechanism_file(kinema_test::sample(name + ".toml")),
                              kinema::DerivationScope::evaluation),
           {}, {}};
  std::vector<double> inputs;
  for (double deg = 0; deg < 360 - 1e-9; deg += step_deg) inputs.push_back(deg * kinema::kPi / 180);
  kinema::SweepSettings settings;
  settings.rate = s.model.system.input.rate_value;
  settings.second_rate = s.model.system.input.second_rate_value;
  s.rows = kinema::solve_sweep(s.model.kinematics, inputs, settings);
  s.resolving = *kinema::resolving(s.model, &s.rows);
  return s;
}

const kinema::Resolving::Parameter& parameter(const Solved& s, const std::string& name) {
  for (const kinema::Resolving::Parameter& p : s.resolving.parameters)
    if (p.name == name) return p;
  FAIL("no parameter " << name);
  return s.resolving.parameters.front();
}

double value(const Solved& s, const std::string& name) { return parameter(s, name).value; }

void check_end(double found, double expected, const std::string& what) {
  INFO(what << ": found " << found << ", by hand " << expected);
  CHECK(std::fabs(found - expected) <= kRelative * std::fabs(expected));
}

}  // namespace

TEST_CASE("slider ranges: every value's band ends where a gap opens between two values of the run") {
  // A run from 1 deg in 3 deg steps has no value at 180 deg: a coupler just short of
  // d + a - c opens a gap around 180 deg between 178 and 181 deg, each value still
  // assembling. The motion no longer runs through the run: b's band starts at 0.06 m and
  // d's ends at b + c - a = 0.16 m (they were 0.0599957 and 0.1600049, gaps stepped over).
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_file(kinema_test::sample("four_bar.toml")),
                                                 kinema::DerivationScope::evaluation);
  std::vector<double> inputs;
  for (double deg = 1; deg < 360; deg += 3) inputs.push_back(deg * kinema::kPi / 180);
  kinema::SweepSettings settings;
  settings.rate = model.system.input.rate_value;
  const kinema::MotionTable rows = kinema::solve_sweep(model.kinematics, inputs, settings);
  const kinema::Resolving resolving = *kinema::resolving(model, &rows);
  for (const kinema::Resolving::Parameter& p : resolving.parameters) {
    if (p.name == "b") check_end(p.range.whole_min, 0.06, "b, every value");
    if (p.name == "d") check_end(p.range.whole_max, 0.16, "d, every value");
  }
}

TEST_CASE("slider ranges: the four-bar's links end where the loop stops closing; an angle that opens none goes half a turn") {
  // Rows at 0 and 180 deg: the crank pin's distance from the rocker's pivot s runs over
  // [d - a, d + a]; the loop closes where |b - c| <= s <= b + c.
  const Solved s = solved_turn("four_bar", 4);
  const double a = value(s, "a"), b = value(s, "b"), c = value(s, "c"), d = value(s, "d");
  const double s_min = d - a, s_max = d + a;
  const kinema::SliderRange& coupler = parameter(s, "b").range;
  check_end(coupler.whole_min, std::max(c - s_min, s_max - c), "b, every value");
  check_end(coupler.whole_max, c + s_min, "b, every value");
  check_end(coupler.max, c + s_max, "b, one value");
  CHECK(coupler.min == b / 20);  // the loop closes somewhere for any shorter coupler: the cap
  const kinema::SliderRange& rocker = parameter(s, "c").range;
  check_end(rocker.whole_min, std::max(b - s_min, s_max - b), "c, every value");
  check_end(rocker.whole_max, b + s_min, "c, every value");
  check_end(rocker.max, b + s_max, "c, one value");
  CHECK(rocker.min == c / 20);
  // The crank turns fully while d + a <= b + c and d - a >= |b - c| (Grashof's crank).
  const kinema::SliderRange& crank = parameter(s, "a").range;
  check_end(crank.whole_max, std::min(b + c - d, d - std::fabs(b - c)), "a, every value");
  CHECK(crank.whole_min == a / 20);
  CHECK(crank.max == 5 * a);  // the loop closes somewhere up to a = b + c + d, past the cap
  // The ground: every value while a + |b - c| <= d <= b + c - a, one value while d - a <= b + c.
  const kinema::SliderRange& ground = parameter(s, "d").range;
  check_end(ground.whole_min, a + std::fabs(b - c), "d, every value");
  check_end(ground.whole_max, b + c - a, "d, every value");
  check_end(ground.max, b + c + a, "d, one value");
  // The coupler point's angle opens no loop: half a turn either way, every value assembling.
  const kinema::Resolving::Parameter& delta = parameter(s, "delta");
  CHECK(delta.range.min == delta.value - kinema::kPi);
  CHECK(delta.range.max == delta.value + kinema::kPi);
  CHECK(delta.range.whole_min == delta.range.min);
  CHECK(delta.range.whole_max == delta.range.max);
}

TEST_CASE("slider ranges: the slider-crank's crank turns fully up to the rod's length less the offset") {
  // The rod closes where |a sin(theta) - e| <= b; 90 and 270 deg are rows.
  const Solved s = solved_turn("slider_crank", 2);
  const double a = value(s, "a"), b = value(s, "b"), e = value(s, "e");
  const kinema::SliderRange& crank = parameter(s, "a").range;
  check_end(crank.whole_max, b - e, "a, every value");
  CHECK(crank.max == 5 * a);  // at theta = 0 the rod reaches the line for any crank: the cap
  const kinema::SliderRange& rod = parameter(s, "b").range;
  check_end(rod.whole_min, a + e, "b, every value");
  CHECK(rod.min == b / 20);
  CHECK(rod.whole_max == 5 * b);
}
