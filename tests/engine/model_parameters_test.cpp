// engine/model's with_parameters and the facade's: a model with other parameter values
// gives the numbers of the file edited to them (every value, rate, second rate, point
// and frame over a sweep), derives and compiles nothing, shares the tape, and names
// what it refuses.
#include <doctest/doctest.h>

#include <kinema/kinema.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/base/work_count.hpp"
#include "engine/model.hpp"
#include "engine/numeric/circuit.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

using kinema::Model;
using kinema::MotionTable;
using kinema::Work;

namespace {

using Values = std::vector<std::pair<std::string, double>>;
using Edits = std::vector<std::pair<std::string, std::string>>;

Model sample_model(const std::string& name) {
  return kinema::make_model(kinema::read_mechanism_file(kinema_test::sample(name)), kinema::DerivationScope::evaluation);
}

// The sample's text with each edit (first occurrence) made, loaded as a model.
Model edited_model(const std::string& name, const Edits& edits) {
  std::string text = kinema_test::read_file(kinema_test::sample(name));
  for (const auto& [from, to] : edits) text = kinema_test::replaced(from, to, text);
  return kinema::make_model(kinema::read_mechanism_text(text, name), kinema::DerivationScope::evaluation);
}

std::vector<double> inputs_between(double first, double last, std::size_t count) {
  std::vector<double> inputs;
  for (std::size_t i = 0; i < count; ++i) inputs.push_back(first + (last - first) * double(i) / double(count - 1));
  return inputs;
}

// Every row of one column of a equals b's to 1e-12 of the column's largest magnitude
// (a value near zero is compared with the column's size, not its own).
void check_column(const double* a, const double* b, std::size_t rows, const std::string& what) {
  double largest = 0;
  for (std::size_t r = 0; r < rows; ++r) largest = std::max({largest, std::fabs(a[r]), std::fabs(b[r])});
  for (std::size_t r = 0; r < rows; ++r) {
    INFO(what << " row " << r << ": " << a[r] << " vs " << b[r]);
    CHECK(std::fabs(a[r] - b[r]) <= 1e-12 * largest);
  }
}

void check_same_tables(const MotionTable& a, const MotionTable& b) {
  REQUIRE(a.size() == b.size());
  std::size_t ok = 0;
  for (std::size_t r = 0; r < a.size(); ++r) {
    CHECK(a.status(r) == b.status(r));
    ok += a.status(r) == kinema::Status::ok;
  }
  CHECK(ok == a.size());  // the sweeps are chosen to assemble everywhere: every number compared
  for (std::size_t i = 0; i < a.unknown_count(); ++i) {
    check_column(a.q_column(i), b.q_column(i), a.size(), "q" + std::to_string(i));
    check_column(a.qd_column(i), b.qd_column(i), a.size(), "qd" + std::to_string(i));
    check_column(a.qdd_column(i), b.qdd_column(i), a.size(), "qdd" + std::to_string(i));
  }
  for (std::size_t p = 0; p < a.point_count(); ++p) {
    for (std::size_t k = 0; k < 3 * a.point(0, p).dimension; ++k)
      check_column(a.point_column(p, k), b.point_column(p, k), a.size(), "point " + std::to_string(p));
  }
  for (std::size_t f = 0; f < a.frame_count(); ++f) {
    for (std::size_t k = 0; k < 6; ++k)
      check_column(a.frame_column(f, k), b.frame_column(f, k), a.size(), "frame " + std::to_string(f));
  }
}

struct WorkCounts {
  std::uint64_t compiled = kinema::work_done_in_process(Work::tape_compile);
  std::uint64_t differentiated = kinema::work_done_in_process(Work::differentiation);
  std::uint64_t dyads_derived = kinema::work_done_in_process(Work::dyad_derivation);
  std::uint64_t formulas_read = kinema::work_done_in_process(Work::formula_read);
};

// with_parameters on the sample equals the edited file over the sweep, and neither the
// copy nor its sweep derived, compiled or read a formula.
void check_equals_edited_file(const std::string& name, const Values& values, const Edits& edits,
                              const std::vector<double>& inputs) {
  const Model original = sample_model(name);
  const Model edited = edited_model(name, edits);
  const WorkCounts before;
  const Model copy = kinema::with_parameters(original, values);
  const MotionTable table = kinema::solve_motion(copy, inputs);
  const WorkCounts after;
  CHECK(after.compiled == before.compiled);
  CHECK(after.differentiated == before.differentiated);
  CHECK(after.dyads_derived == before.dyads_derived);
  CHECK(after.formulas_read == before.formulas_read);
  CHECK(&copy.kinematics.evaluator() == &original.kinematics.evaluator());  // shared, not copied
  CHECK(copy.system.length_scale == edited.system.length_scale);
  for (std::size_t p = 0; p < copy.system.parameters.size(); ++p) {
    INFO(copy.system.parameters[p].symbol.get_name());
    CHECK(copy.system.parameters[p].value == doctest::Approx(edited.system.parameters[p].value).epsilon(1e-15));
  }
  check_same_tables(table, kinema::solve_motion(edited, inputs));
  // The original keeps its own numbers: nothing of it was changed through the shared tape.
  check_same_tables(kinema::solve_motion(original, inputs), kinema::solve_motion(sample_model(name), inputs));
}

constexpr double kDeg = kinema::kPi / 180;

}  // namespace

TEST_CASE("with_parameters: a vector-loop four-bar equals its file edited to the same lengths and angle") {
  check_equals_edited_file("four_bar.toml", {{"b", 0.123}, {"delta", 25 * kDeg}},
                           {{"b = \"120 mm\"", "b = \"123 mm\""}, {"delta = \"30 deg\"", "delta = \"25 deg\""}},
                           inputs_between(0, 2 * kinema::kPi, 73));
}

TEST_CASE("with_parameters: a slider-crank equals its file edited, the length scale following the longest link") {
  // b is the longest length: the edited file's length scale (tolerances, continuation) is 0.2 m.
  check_equals_edited_file("slider_crank.toml", {{"b", 0.2}, {"e", 0.012}},
                           {{"b = \"150 mm\"", "b = \"200 mm\""}, {"e = \"10 mm\"", "e = \"12 mm\""}},
                           inputs_between(0, 2 * kinema::kPi, 73));
}

TEST_CASE("with_parameters: a joints file equals its file edited, a formula parameter following (EF = CE)") {
  // Within the sketch's 1 % so that the edited file reads; EF = "CE" and D-E = "CD + CE" follow.
  const Values values{{"CE", 0.231}, {"BC", 0.402}};
  check_equals_edited_file("problem_4_4_joints.toml", values,
                           {{"CE = \"0.230 m\"", "CE = \"0.231 m\""}, {"BC = \"0.400 m\"", "BC = \"0.402 m\""}},
                           inputs_between(0, 2 * kinema::kPi, 73));
  const Model copy = kinema::with_parameters(sample_model("problem_4_4_joints.toml"), values);
  const auto value_of = [&](const std::string& name) {
    return copy.system.parameters[kinema::written_parameter_index(copy.system, name)].value;
  };
  CHECK(value_of("EF") == 0.231);
  CHECK(copy.kinematics.closed_form() == nullptr);  // the plan's numbers were the file's
  kinema::CircuitSettings circuit;
  circuit.step = 1 * kDeg;
  CHECK_THROWS_WITH_AS(kinema::solve_circuit(copy.kinematics, circuit), doctest::Contains("closed form"),
                       kinema::InputError);
}

TEST_CASE("with_parameters: a spatial chain equals its file edited") {
  check_equals_edited_file("robot_arm_seed000.toml", {{"L2", 0.65}, {"alpha", 50 * kDeg}},
                           {{"L2 = \"0.6 m\"", "L2 = \"0.65 m\""}, {"alpha = \"60 deg\"", "alpha = \"50 deg\""}},
                           inputs_between(0, 3, 31));
}

TEST_CASE("with_parameters: a later value for the same name wins, and the rest keep the file's") {
  const Model original = sample_model("four_bar.toml");
  const Model copy = kinema::with_parameters(original, {{"c", 0.07}, {"c", 0.085}});
  for (std::size_t p = 0; p < copy.system.parameters.size(); ++p) {
    const std::string name = copy.system.parameters[p].symbol.get_name();
    INFO(name);
    CHECK(copy.system.parameters[p].value == (name == "c" ? 0.085 : original.system.parameters[p].value));
    CHECK(copy.kinematics.parameter_values()[p] == copy.system.parameters[p].value);
  }
}

TEST_CASE("with_parameters refuses, naming it, a parameter the file does not write, one kinema made, a value not finite") {
  const Model four_bar = sample_model("four_bar.toml");
  CHECK_THROWS_WITH_AS(kinema::with_parameters(four_bar, {{"bb", 0.1}}),
                       doctest::Contains("no parameter named \"bb\" (there are: a, b, c, d, p, delta)"),
                       kinema::InputError);
  CHECK_THROWS_WITH_AS(kinema::with_parameters(four_bar, {{"b", NAN}}), doctest::Contains("parameter \"b\""),
                       kinema::InputError);
  // A spatial chain's starting motion is a parameter kinema made, not one the file writes.
  const Model arm = sample_model("robot_arm_seed000.toml");
  CHECK_THROWS_WITH_AS(kinema::with_parameters(arm, {{"theta4_0", 0.1}}),
                       doctest::Contains("no parameter named \"theta4_0\""), kinema::InputError);
  // A joints file whose sketch gives a length (AB no longer stated): its dimensions change the
  // sketch's numbers too, which only reading the file again gives.
  const std::string text = kinema_test::replaced(
      "1 = { joints = [\"A\", \"B\"], length = \"AB\" }", "1 = { joints = [\"A\", \"B\"] }",
      kinema_test::read_file(kinema_test::sample("problem_4_4_joints.toml")));
  const Model sketched = kinema::make_model(kinema::read_mechanism_text(text, "sketched.toml"));
  CHECK_THROWS_WITH_AS(kinema::with_parameters(sketched, {{"BC", 0.402}}), doctest::Contains("from its sketch"),
                       kinema::InputError);
}

TEST_CASE("MechanismModel::with_parameters reads quantities with units and equals the edited file") {
  const kinema::MechanismModel four_bar(kinema_test::sample("four_bar.toml"));
  const kinema::MechanismModel copy = four_bar.with_parameters({{"b", "0.123 m"}, {"delta", "25 deg"}});
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  text = kinema_test::replaced("b = \"120 mm\"", "b = \"123 mm\"", text);
  text = kinema_test::replaced("delta = \"30 deg\"", "delta = \"25 deg\"", text);
  const kinema::MechanismModel edited = kinema::MechanismModel::from_toml(text);
  for (const char* at : {"0 deg", "100 deg", "250 deg"}) {
    const kinema::Solution a = copy.solve(at), b = edited.solve(at);
    for (std::size_t i = 0; i < a.values().size(); ++i) {
      CHECK(a.values()[i] == doctest::Approx(b.values()[i]).epsilon(1e-12));
      CHECK(a.rates()[i] == doctest::Approx(b.rates()[i]).epsilon(1e-12));
      CHECK(a.second_rates()[i] == doctest::Approx(b.second_rates()[i]).epsilon(1e-12));
    }
    CHECK(a.point("P").acceleration[0] == doctest::Approx(b.point("P").acceleration[0]).epsilon(1e-12));
  }
  CHECK(copy.solve("100 deg").value("theta3") != four_bar.solve("100 deg").value("theta3"));
  CHECK_THROWS_WITH_AS(four_bar.with_parameters({{"b", "30 deg"}}),
                       doctest::Contains("parameter \"b\" is a length, but \"30 deg\" is an angle"), kinema::Error);
  CHECK_THROWS_WITH_AS(four_bar.with_parameters({{"b", "0.12"}}), doctest::Contains("give its unit"), kinema::Error);
  CHECK_THROWS_WITH_AS(four_bar.with_parameters({{"q", "1 m"}}), doctest::Contains("no parameter named \"q\""),
                       kinema::Error);
}
