// Exact sensitivities (engine/numeric/sensitivity, engine/analysis/sensitivities): every
// derivative column of every parameter a sample writes equals central finite
// differences of the solved output values in that parameter (the model re-solved with
// with_parameters at p + h and p - h) over a sweep, vector loops, joints and links
// (closed form, formula parameters; their blocks, sliders on moving guides and guide
// points) and spatial chains alike; and what is refused.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <regex>
#include <string>
#include <vector>

#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/sensitivities.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/units.hpp"
#include "engine/model.hpp"
#include "engine/numeric/sensitivity.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

using kinema::Model;
using kinema::MotionTable;

namespace {

Model sample_model(const std::string& name) {
  return kinema::make_model(kinema::read_mechanism_file(kinema_test::sample(name)), kinema::DerivationScope::evaluation);
}

std::vector<double> inputs_between(double first, double last, std::size_t count) {
  std::vector<double> inputs;
  for (std::size_t i = 0; i < count; ++i) inputs.push_back(first + (last - first) * double(i) / double(count - 1));
  return inputs;
}

// All rows of a table of the model in output units (result_rows), row after row.
std::vector<double> output_rows(const Model& model, const MotionTable& table) {
  std::vector<double> values(kinema::result_column_count(model.system) * table.size());
  kinema::result_rows(model.system, kinema::OutputScale(model.system), table, 0, table.size(), values.data());
  return values;
}

// SI units of a parameter per its output unit (the file's length unit, deg, or 1).
double parameter_output_unit(const kinema::SystemParameter& p, const kinema::OutputScale& scale) {
  return p.dimension == kinema::Dimension::length ? scale.length
         : p.dimension == kinema::Dimension::angle ? kinema::kRadiansPerDegree
                                                    : 1.0;
}

// Step of the central differences: 1e-5 of the parameter's size (lengths: at least of the
// length scale; angles and plain numbers: 1e-5). The differences' truncation error is then
// ~1e-10 of a derivative and the solves' rounding (1e-14 of the length scale) ~1e-9.
double difference_step(const kinema::SystemParameter& p, double length_scale) {
  return 1e-5 * (p.dimension == kinema::Dimension::length ? std::max(std::fabs(p.value), length_scale) : 1.0);
}

// Every sensitivity column of every written parameter of the sample equals the central
// difference of its column to 1e-6 of the column's scale: the larger of its largest
// derivative over the sweep and the size a derivative of it has (its largest value per the
// parameter's size). So a derivative near zero is compared with its column's size, and one
// that is zero everywhere with the size of the differences' rounding (~1e-8 of that).
// The model with one parameter moved (default: with_parameters; a joints file whose sketch
// gave lengths is read again from its text edited).
using Moved = std::function<Model(const Model&, const std::string& name, double value)>;

void check_against_finite_differences(const std::string& sample, const std::vector<double>& inputs, const Model& model,
                                      const Moved& moved, const std::vector<std::string>& only = {}) {
  INFO(sample);
  const kinema::ConstraintSystem& system = model.system;
  const kinema::OutputScale scale(system);
  const std::size_t width = kinema::result_column_count(system), rows = inputs.size();
  const std::vector<kinema::ResultColumn> columns = kinema::result_columns(system, scale);
  const MotionTable table = kinema::solve_motion(model, inputs);
  std::size_t compared = 0;
  for (const kinema::SystemParameter& p : system.parameters) {
    if (!p.written) continue;
    const std::string name = p.symbol.get_name();
    if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
    INFO("parameter " << name);
    const kinema::Sensitivities sensitivities(model, kinema::sensitivity_columns(system, {name}));
    const std::size_t asked = sensitivities.columns().size();
    REQUIRE(asked == kinema::differentiable_columns(system).size());
    std::vector<double> exact(asked * rows);
    sensitivities.rows(table, 0, rows, exact.data());
    const double h = difference_step(p, system.length_scale);
    const Model above = moved(model, name, p.value + h), below = moved(model, name, p.value - h);
    const MotionTable above_table = kinema::solve_motion(above, inputs), below_table = kinema::solve_motion(below, inputs);
    for (std::size_t r = 0; r < rows; ++r)
      REQUIRE((table.status(r) == kinema::Status::ok && above_table.status(r) == kinema::Status::ok &&
               below_table.status(r) == kinema::Status::ok));
    const std::vector<double> plus = output_rows(above, above_table), minus = output_rows(below, below_table);
    const double step = 2 * h / parameter_output_unit(p, scale);  // in the parameter's output unit
    const double size = h / 1e-5 / parameter_output_unit(p, scale);
    for (std::size_t k = 0; k < asked; ++k) {
      const kinema::SensitivityColumn& column = sensitivities.columns()[k];
      INFO(column.named.name << " [" << column.named.unit << "]");
      CHECK(column.named.name == "d_" + columns[column.column].name + "_d_" + name);
      double largest = 0;
      for (std::size_t r = 0; r < rows; ++r)
        largest = std::max({largest, std::fabs(exact[r * asked + k]), std::fabs(plus[r * width + column.column]) / size});
      for (std::size_t r = 0; r < rows; ++r) {
        double change = plus[r * width + column.column] - minus[r * width + column.column];
        if (columns[column.column].unit == "deg") change = std::remainder(change, 360.0);  // wrapped at +-180
        const double difference = change / step, value = exact[r * asked + k];
        INFO("row " << r << ": exact " << value << ", differences " << difference);
        CHECK(std::fabs(value - difference) <= 1e-6 * largest);
        ++compared;
      }
    }
  }
  CHECK(compared > 0);
}

void check_against_finite_differences(const std::string& sample, const std::vector<double>& inputs) {
  check_against_finite_differences(sample, inputs, sample_model(sample), [](const Model& model, const std::string& name, double value) {
    return kinema::with_parameters(model, {{name, value}});
  });
}

// A joints file's text with parameter `name` written as `value` (SI, in mm), read again.
Model read_with(const std::string& text, const std::string& name, double value) {
  const std::regex line("\\n" + name + " = \"[^\"]*\"");
  REQUIRE(std::regex_search(text, line));
  const std::string edited = std::regex_replace(text, line, "\n" + name + " = \"" + kinema::format_round_trip(value * 1e3) + " mm\"",
                                                std::regex_constants::format_first_only);
  return kinema::make_model(kinema::read_mechanism_text(edited, "edited.toml"), kinema::DerivationScope::evaluation);
}

}  // namespace

TEST_CASE("engine/numeric/sensitivity: every derivative column equals finite differences, vector loops") {
  const std::vector<double> turn = inputs_between(0, kinema::from_degrees(330), 12);
  check_against_finite_differences("four_bar.toml", turn);
  check_against_finite_differences("slider_crank.toml", turn);
  check_against_finite_differences("problem_4_4_six_bar.toml", turn);
}

TEST_CASE("engine/numeric/sensitivity: every derivative column equals finite differences, joints and links") {
  // Solved dyad by dyad in closed form, EF = "CE" and Lc = "CD" following (d/dCE moves F's link too).
  const Model model = sample_model("problem_4_4_joints.toml");
  REQUIRE(model.kinematics.closed_form() != nullptr);
  check_against_finite_differences("problem_4_4_joints.toml", inputs_between(0, kinema::from_degrees(330), 12));
  // The joints files' own columns: sliders on moving guides (relative velocity, relative and
  // Coriolis acceleration, the guide's point under the slider), blocks and relative turnings.
  for (const char* sample : {"example_4_1_joints.toml", "example_4_2_joints.toml", "problem_3_22_joints.toml"}) {
    const Model joints = sample_model(sample);
    const std::vector<kinema::ResultColumn> columns = kinema::result_columns(joints.system, kinema::OutputScale(joints.system));
    CHECK(kinema::differentiable_columns(joints.system).size() == columns.size() - kinema::kInputColumns);
  }
  check_against_finite_differences("example_4_1_joints.toml", inputs_between(kinema::from_degrees(5), kinema::from_degrees(85), 6));
  check_against_finite_differences("example_4_2_joints.toml", inputs_between(kinema::from_degrees(5), kinema::from_degrees(85), 6));
  check_against_finite_differences("problem_3_22_joints.toml",
                                   inputs_between(kinema::from_degrees(-150), kinema::from_degrees(-90), 6));
}

TEST_CASE("engine/numeric/sensitivity: every derivative column equals finite differences, spatial chains") {
  check_against_finite_differences("robot_arm_seed000.toml", inputs_between(0, 1, 6));     // open: points and frames
  check_against_finite_differences("rssr_spatial_four_bar.toml", inputs_between(0, kinema::from_degrees(330), 12));
}

TEST_CASE("engine/numeric/sensitivity: a formula parameter given alone does not follow its formula") {
  // d/dEF with EF given (its formula "CE" dropped, as with_parameters drops it) leaves CE's
  // links alone, and d/dCE = its own part + d/dEF's (EF follows CE one for one).
  const Model model = sample_model("problem_4_4_joints.toml");
  const MotionTable table = kinema::solve_motion(model, {kinema::from_degrees(30)});
  const auto values = [&](const std::string& asked) {
    const kinema::Sensitivities s(model, kinema::sensitivity_columns(model.system, {asked}));
    std::vector<double> row(s.columns().size());
    s.rows(table, 0, 1, row.data(), true);
    return row;
  };
  const std::vector<double> ce = values("CE"), ef = values("EF");
  const std::vector<double> ce_alone = [&] {  // CE with EF held: EF given its value
    const Model held = kinema::with_parameters(model, {{"EF", model.system.parameters[kinema::written_parameter_index(model.system, "EF")].value}});
    const MotionTable t = kinema::solve_motion(held, {kinema::from_degrees(30)});
    // Its derivatives are not the file's (EF no longer follows CE), though it shares the tape.
    CHECK(&kinema::ParameterSensitivity(held.system, held.derivation, held.kinematics, "CE").tape() !=
          &kinema::ParameterSensitivity(model.system, model.derivation, model.kinematics, "CE").tape());
    const kinema::Sensitivities s(held, kinema::sensitivity_columns(held.system, {"CE"}));
    std::vector<double> row(s.columns().size());
    s.rows(t, 0, 1, row.data(), true);
    return row;
  }();
  REQUIRE(ce.size() == ef.size());
  REQUIRE(ce.size() == ce_alone.size());
  double moved = 0;
  for (std::size_t k = 0; k < ce.size(); ++k) {
    CHECK(ce[k] == doctest::Approx(ce_alone[k] + ef[k]).epsilon(1e-9).scale(1.0));
    moved = std::max(moved, std::fabs(ef[k]));
  }
  CHECK(moved > 0);  // EF moves something: the sum above is not trivially ce_alone's
}

TEST_CASE("engine/numeric/sensitivity: columns asked one by one, named and in the output units") {
  const Model model = sample_model("four_bar.toml");
  const std::vector<kinema::SensitivityColumn> one = kinema::sensitivity_columns(model.system, {"omega3:b"});
  REQUIRE(one.size() == 1);
  CHECK(one[0].named.name == "d_omega3_d_b");
  CHECK(one[0].named.unit == "rad/s/mm");  // the column's unit per the parameter's output unit
  const std::vector<kinema::SensitivityColumn> angle = kinema::sensitivity_columns(model.system, {"theta3:delta", "P_speed:b"});
  REQUIRE(angle.size() == 2);
  CHECK(angle[0].named.unit == "deg/deg");
  CHECK(angle[1].named.unit == "mm/s/mm");
  // Asked twice (alone and with all of b's): one column.
  const std::vector<kinema::SensitivityColumn> all = kinema::sensitivity_columns(model.system, {"omega3:b", "b"});
  CHECK(all.size() == kinema::differentiable_columns(model.system).size());
  CHECK(all[0].named.name == "d_omega3_d_b");
}

TEST_CASE("engine/numeric/sensitivity: a parameter's derivatives are compiled once for every model sharing the tape") {
  // The Python module asks per call and a study per design: the second asking must not
  // derive again, and a with_parameters copy's derivatives (the same tape, its own values)
  // must still be its own.
  const Model model = sample_model("four_bar.toml");
  const kinema::ParameterSensitivity first(model.system, model.derivation, model.kinematics, "b");
  const kinema::ParameterSensitivity again(model.system, model.derivation, model.kinematics, "b");
  CHECK(&first.tape() == &again.tape());
  const kinema::ParameterSensitivity other(model.system, model.derivation, model.kinematics, "c");
  CHECK(&other.tape() != &first.tape());
  const std::size_t b = kinema::written_parameter_index(model.system, "b");
  const double changed = model.system.parameters[b].value * 1.1, h = 1e-5 * model.system.length_scale;
  const Model copy = kinema::with_parameters(model, {{"b", changed}});
  const kinema::ParameterSensitivity copied(copy.system, copy.derivation, copy.kinematics, "b");
  CHECK(&copied.tape() == &first.tape());
  const std::vector<double> inputs = inputs_between(0.1, 6.0, 7);
  const MotionTable table = kinema::solve_motion(copy, inputs);
  const Model above = kinema::with_parameters(model, {{"b", changed + h}});
  const Model below = kinema::with_parameters(model, {{"b", changed - h}});
  const MotionTable plus = kinema::solve_motion(above, inputs), minus = kinema::solve_motion(below, inputs);
  kinema::SensitivityWorkspace workspace(copied);
  kinema::StateDerivatives derivatives;
  for (std::size_t r = 0; r < inputs.size(); ++r) {
    REQUIRE(workspace.at(table, r, derivatives));
    for (Eigen::Index i = 0; i < derivatives.qd.size(); ++i) {
      const double difference = (plus.qd(r)[i] - minus.qd(r)[i]) / (2 * h);
      INFO("row " << r << " rate " << i);
      CHECK(derivatives.qd[i] == doctest::Approx(difference).epsilon(1e-6).scale(std::fabs(plus.qd(r)[i]) / model.system.length_scale));
    }
  }
}

// Issue 45: the triple rocker's sketch gives kinema x_D, r_2_P and beta_2_P (written there as
// quantities: constants of the file whatever its parameters). Its derivatives in AB, BC and
// CD were refused for them; they equal central differences of the file read again with the
// parameter edited. A parameter the sketch places a joint with (P at ["Px", ...]) moves
// r_2_P and beta_2_P: refused, naming them, while AB is still allowed.
TEST_CASE("engine/numeric/sensitivity: a joints file with lengths from its sketch, in the parameters they do not follow") {
  const std::string text = kinema_test::read_file(kinema_test::sample("triple_rocker_circuit.toml"));
  const Model model = kinema::make_model(kinema::read_mechanism_text(text, "triple_rocker_circuit.toml"),
                                         kinema::DerivationScope::evaluation);
  std::vector<std::string> made;
  for (const kinema::SystemParameter& p : model.system.parameters)
    if (!p.written) made.push_back(p.symbol.get_name());
  CHECK(made == std::vector<std::string>{"x_D", "r_2_P", "beta_2_P"});
  const Moved reread = [&](const Model&, const std::string& name, double value) { return read_with(text, name, value); };
  check_against_finite_differences("triple_rocker_circuit.toml", inputs_between(kinema::from_degrees(40), kinema::from_degrees(320), 8),
                                   model, reread, {"AB", "BC", "CD"});
  const auto refusal = [](const std::string& file_text, const std::string& name) {
    const Model m = kinema::make_model(kinema::read_mechanism_text(file_text, "placed.toml"), kinema::DerivationScope::evaluation);
    try {
      kinema::Sensitivities(m, kinema::sensitivity_columns(m.system, {name}));
    } catch (const kinema::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // P placed with a parameter: its offsets on link 2 follow Px, the ground pivot's x does not.
  const std::string placed = kinema_test::replaced(
      "P = { link = \"2\", at = [\"37.034762 mm\"", "P = { link = \"2\", at = [\"Px\"",
      kinema_test::replaced("CD = \"45 mm\"\n", "CD = \"45 mm\"\nPx = \"37.034762 mm\"\n", text));
  const std::string message = refusal(placed, "Px");
  CAPTURE(message);
  CHECK(message.find("no sensitivity in \"Px\" for this joints file: kinema took r_2_P, beta_2_P from its sketch, which "
                     "places joints with Px") != std::string::npos);
  CHECK(message.find("x_D") == std::string::npos);
  CHECK(refusal(placed, "AB").empty());
  // And through the command line.
  const kinema_test::CommandResult run =
      kinema_test::run_kinema({"eval", kinema_test::sample("triple_rocker_circuit.toml"), "--sensitivity", "omega2:AB"});
  CAPTURE(run.err);
  CHECK(run.exit_status == 0);
  CHECK(run.out.find("d_omega2_d_AB") != std::string::npos);
}

TEST_CASE("engine/numeric/sensitivity: an unknown parameter or column is named with the list of names") {
  const Model model = sample_model("four_bar.toml");
  const auto message = [&](const std::string& asked) {
    try {
      kinema::sensitivity_columns(model.system, {asked});
    } catch (const kinema::InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string parameter = message("omega3:bb");
  CHECK(parameter.find("no parameter named \"bb\"") != std::string::npos);
  CHECK(parameter.find("there are: a, b, c, d, p, delta") != std::string::npos);
  const std::string column = message("omega2:b");  // the input's rate is given: no derivative
  CHECK(column.find("no output column named \"omega2\"") != std::string::npos);
  CHECK(column.find("theta3, omega3, alpha3") != std::string::npos);
  CHECK(message("b").empty());
}
