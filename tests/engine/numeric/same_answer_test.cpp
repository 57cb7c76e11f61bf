// Same question, same answer (issue 45): a value's assembly is the file's however it is
// asked (alone, in a list, in a sweep, on a copy), no gap between two values is stepped
// over however narrow, and a periodic angle is reached the short way round in every form.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/model.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<double> turn(double first, double last, double step) {
  std::vector<double> inputs;
  for (double v = first; v <= last + 1e-9; v += step) inputs.push_back(v * kDeg);
  return inputs;
}

std::string digits(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  return out.str();
}

// The same position: angles a whole number of turns apart, lengths equal (scaled).
bool same_position(const kinema::Model& model, const kinema::MotionTable& a, std::size_t ra,
                   const kinema::MotionTable& b, std::size_t rb, std::string& why) {
  // At a singular position (a change point, a toggle) Newton's position is only
  // sqrt(eps)-accurate, whichever way it came.
  const double tolerance =
      a.status(ra) == kinema::Status::singular || b.status(rb) == kinema::Status::singular ? 1e-5 : 1e-8;
  for (std::size_t i = 0; i < a.unknown_count(); ++i) {
    const double x = a.q_column(i)[ra], y = b.q_column(i)[rb];
    const bool angle = model.system.unknowns[i].dimension == kinema::Dimension::angle;
    const double difference = angle ? std::remainder(x - y, 2 * M_PI) : (x - y) / model.kinematics.length_scale();
    if (!(std::fabs(difference) <= tolerance)) {
      why = model.system.unknowns[i].name + ": " + digits(x) + " against " + digits(y);
      return false;
    }
  }
  return true;
}

// Every value of `inputs` asked alone is the sweep's row there: the same status, and where
// the sweep has a position, the same position.
// A sample's own lengths assemble somewhere in the turn (a copy's need not).
void check_alone_equals_sweep(const kinema::Model& model, const std::vector<double>& inputs, const std::string& what,
                              bool assembles = true) {
  const kinema::MotionTable sweep = kinema::solve_motion(model, inputs);
  std::size_t compared = 0;
  for (std::size_t row = 0; row < inputs.size(); ++row) {
    const kinema::MotionTable alone = kinema::solve_motion(model, {inputs[row]});
    INFO(what << " at " << inputs[row] / kDeg << " deg");
    CHECK(kinema::status_name(alone.status(0)) == std::string(kinema::status_name(sweep.status(row))));
    if (sweep.status(row) == kinema::Status::unassembled || alone.status(0) == kinema::Status::unassembled) continue;
    std::string why;
    CHECK_MESSAGE(same_position(model, alone, 0, sweep, row, why), why);
    ++compared;
  }
  if (assembles) CHECK_MESSAGE(compared > 0, what);
}

std::vector<std::string> planar_samples() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kinema_test::sample(""))) {
    if (entry.path().extension() != ".toml") continue;
    const std::string name = entry.path().filename().string();
    if (name.find("_set") != std::string::npos) continue;  // a problem set, not a mechanism
    names.push_back(name);
  }
  return names;
}

// The sample four-bar with coupler b (mm): below 60 mm a triple rocker that cannot pass
// theta2 = 180 deg.
std::string four_bar_with_b(double b_mm) {
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  const std::string from = "b = \"120 mm\"";
  text.replace(text.find(from), from.size(), "b = \"" + digits(b_mm) + " mm\"");
  return text;
}

}  // namespace

TEST_CASE("engine/numeric/same answer: every sample's values alone are its sweep's rows, on copies with lengths changed too") {
  for (const std::string& name : planar_samples()) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name), kinema::DerivationScope::evaluation);
    const bool angle = model.system.input.dimension == kinema::Dimension::angle;
    const std::vector<double> inputs =
        angle ? turn(-180, 180, 15)
              : std::vector<double>{model.system.input.values.empty() ? 0.0 : model.system.input.values.front()};
    if (!angle) continue;  // a slider or time input: the samples' own values are checked elsewhere
    check_alone_equals_sweep(model, inputs, name);
    for (const kinema::SystemParameter& parameter : model.system.parameters) {
      if (!parameter.written || parameter.dimension != kinema::Dimension::length || parameter.formula) continue;
      for (const double factor : {0.6, 0.9, 1.1, 1.4}) {
        std::unique_ptr<kinema::Model> copy;
        try {
          copy = std::make_unique<kinema::Model>(
              kinema::with_parameters(model, {{parameter.symbol.get_name(), parameter.value * factor}}));
        } catch (const kinema::InputError&) {
          continue;  // a joints file whose lengths kinema took from its sketch: no copies
        }
        check_alone_equals_sweep(*copy, inputs, name + " with " + parameter.symbol.get_name() + " x" + std::to_string(factor),
                                 false);
      }
    }
  }
}

TEST_CASE("engine/numeric/same answer: a gap down to 1e-6 of a turn is never stepped over") {
  // a, c, d = 40, 80, 100 mm: with b + c just short of a + d the crank cannot pass 180 deg
  // in a gap of half-width g: (b + c)^2 = a^2 + d^2 + 2 a d cos g.
  for (const double gap_in_turns : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    const double g = M_PI * gap_in_turns;  // half the gap
    const double b = std::sqrt(40.0 * 40 + 100.0 * 100 + 2 * 40.0 * 100 * std::cos(g)) - 80;
    const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(four_bar_with_b(b), "gap.toml"));
    INFO("gap of " << gap_in_turns << " turn, b = " << b << " mm");
    for (const std::vector<double>& run : {std::vector<double>{175 * kDeg, 185 * kDeg}, turn(170, 190, 10)}) {
      const kinema::MotionTable table = kinema::solve_motion(model, run);
      const std::size_t last = table.size() - 1;
      REQUIRE(table.status(0) == kinema::Status::ok);
      REQUIRE(table.status(last) == kinema::Status::ok);
      // 185 deg is reached past the gap, so it says so, and it is the file's assembly there
      // (the value asked alone), not the one across the gap from 175 deg.
      CHECK(table.failure(last).kind == kinema::Failure::Kind::resumed_after_gap);
      const kinema::MotionTable alone = kinema::solve_motion(model, {run.back()});
      std::string why;
      CHECK_MESSAGE(same_position(model, alone, 0, table, last, why), why);
    }
    // Row by row in steps of 1 deg across the gap: the row after it says so.
    const kinema::MotionTable fine = kinema::solve_motion(model, turn(170, 190, 1));
    bool resumed = false;
    for (std::size_t row = 0; row < fine.size(); ++row)
      resumed = resumed || fine.failure(row).kind == kinema::Failure::Kind::resumed_after_gap ||
                fine.status(row) != kinema::Status::ok;
    CHECK(resumed);
  }
}

TEST_CASE("engine/numeric/same answer: a crank through a change point is not a gap") {
  // b + c = a + d exactly: the branches cross at 180 deg (a change point), no gap.
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(four_bar_with_b(60), "change.toml"));
  const kinema::MotionTable table = kinema::solve_motion(model, {175 * kDeg, 185 * kDeg});
  CHECK(table.status(1) == kinema::Status::ok);
  CHECK(table.failure(1).kind == kinema::Failure::Kind::none);
}

TEST_CASE("engine/numeric/same answer: past a change point a turn does not come back to its assembly; a value alone is the sweep's") {
  // d = 80 mm: s + l = 40 + 120 = p + q = 80 + 80, the branches cross at 0 deg. The branch
  // through it comes back a turn on on the other assembly, so the short way round from the
  // guesses' value (through 0 deg) and a sweep over the turn (which meets 0 deg only at its
  // start) disagreed from 221 deg on: a value alone is carried the way that meets no change
  // point.
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  const std::string from = "d = \"100 mm\"";
  text.replace(text.find(from), from.size(), "d = \"80 mm\"");
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(text, "d80.toml"));
  check_alone_equals_sweep(model, turn(0, 359, 1), "d = 80 mm");
  check_alone_equals_sweep(model, turn(-180, 180, 15), "d = 80 mm");
}

TEST_CASE("engine/numeric/same answer: a vector-loop rocker goes the short way round a turn") {
  // A triple rocker (a, b, c, d = 60, 40, 50, 100 mm) that moves within +-62.72 deg: b and
  // c in line there, a^2 + d^2 - 2 a d cos(theta2) = (b + c)^2. Stepping from 0 to 300 deg
  // the long way, it stopped at 62.72 deg.
  const char* const text = R"toml(title = "triple rocker"
[parameters]
a = "60 mm"
b = "40 mm"
c = "50 mm"
d = "100 mm"
[input]
name = "theta2"
rate = "1 rad/s"
[unknowns]
theta3 = "77 deg"
theta4 = "129 deg"
[loops]
ABCD = "a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d"
)toml";
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(text, "rocker.toml"));
  REQUIRE(model.kinematics.periodic_input());
  const kinema::MotionTable list = kinema::solve_motion(model, {0.0, 300 * kDeg});
  REQUIRE(list.status(1) == kinema::Status::ok);  // 300 deg is -60 deg
  CHECK(list.failure(1).kind == kinema::Failure::Kind::none);
  const kinema::MotionTable minus = kinema::solve_motion(model, {0.0, -60 * kDeg});
  std::string why;
  CHECK_MESSAGE(same_position(model, list, 1, minus, 1, why), why);
}

TEST_CASE("engine/numeric/same answer: a sweep back after a gap is on the file's assembly, a turn on equals its start") {
  // c = 50 mm: a triple rocker; 40 deg open (the file's), the sweep leaves and comes back.
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  text.replace(text.find("c = \"80 mm\""), 11, "c = \"50 mm\"");
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(text, "c50.toml"));
  const kinema::MotionTable table = kinema::solve_motion(model, turn(40, 400, 10));
  const std::size_t last = table.size() - 1;
  REQUIRE(table.status(0) == kinema::Status::ok);
  REQUIRE(table.status(last) == kinema::Status::ok);
  bool gap = false;
  for (std::size_t row = 0; row < table.size(); ++row) gap = gap || table.status(row) != kinema::Status::ok;
  CHECK(gap);
  std::string why;
  CHECK_MESSAGE(same_position(model, table, 0, table, last, why), why);
}
