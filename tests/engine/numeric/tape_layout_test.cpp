// engine/numeric/tape_layout: the register and output indices, and that they
// are where Kinematics compiles things: the four-bar's tape evaluated at a
// closed-form position gives Phi ~ 0, Phi_q and Phi_theta equal to the
// derivation's, gamma and the points equal to GiNaC's evaluation.
#include <doctest/doctest.h>

#include <set>

#include "engine/numeric/tape_layout.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::TapeLayout;
using kinema_unit::kDeg;

TEST_CASE("engine/numeric/tape_layout: input registers and outputs, counted by hand") {
  TapeLayout layout;
  layout.parameter_count = 4;
  layout.unknown_count = 2;
  layout.point_dimensions = {2, 3, 2};
  CHECK(layout.parameter(3) == 3);
  CHECK(layout.input() == 4);
  CHECK(layout.rate() == 5);
  CHECK(layout.second_rate() == 6);
  CHECK(layout.q(0) == 7);
  CHECK(layout.q(1) == 8);
  CHECK(layout.qd(0) == 9);
  CHECK(layout.qd(1) == 10);
  CHECK(layout.qdd(0) == 11);
  CHECK(layout.qdd(1) == 12);
  CHECK(layout.input_register_count() == 13);

  // Position stage: Phi (2), Phi_q column-major (4), Phi_theta (2).
  CHECK(layout.phi(1) == 1);
  CHECK(layout.phi_q(0, 0) == 2);
  CHECK(layout.phi_q(1, 0) == 3);
  CHECK(layout.phi_q(0, 1) == 4);
  CHECK(layout.phi_q(1, 1) == 5);
  CHECK(layout.phi_theta(0) == 6);
  CHECK(layout.phi_theta(1) == 7);
  CHECK(layout.position_output_count() == 8);

  // Points: 3 * dimension values each.
  CHECK(layout.point_output(0) == 0);
  CHECK(layout.point_output(1) == 6);
  CHECK(layout.point_output(2) == 15);
  CHECK(layout.point_output_count() == 21);

  // Levels: parameters 0, the input and its rates 1, q 2, qd 3, qdd 4.
  const std::vector<int> levels = layout.input_levels();
  REQUIRE(levels.size() == 13);
  const std::vector<int> expected = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3, 3, 4, 4};
  CHECK(levels == expected);

  // Every index of the position stage is used exactly once.
  TapeLayout three;
  three.unknown_count = 3;
  std::set<std::size_t> seen;
  for (std::size_t i = 0; i < 3; ++i) {
    seen.insert(three.phi(i));
    seen.insert(three.phi_theta(i));
    for (std::size_t j = 0; j < 3; ++j) seen.insert(three.phi_q(i, j));
  }
  CHECK(seen.size() == three.position_output_count());
  CHECK(*seen.rbegin() == three.position_output_count() - 1);
}

TEST_CASE("engine/numeric/tape_layout: Kinematics compiles the four-bar where the layout says") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::ConstraintSystem& s = model.system;
  const kinema::Derivation& d = model.derivation;
  const kinema::Kinematics& k = model.kinematics;
  const TapeLayout& layout = k.layout();
  const auto& tape = k.evaluator();
  const std::size_t n = 2;

  REQUIRE(layout.parameter_count == s.parameters.size());
  REQUIRE(layout.unknown_count == n);
  CHECK(layout.point_dimensions == std::vector<std::size_t>{2, 2, 2});
  CHECK(tape.input_count() == layout.input_register_count());
  REQUIRE(tape.stage_count() == TapeLayout::kStageCount);
  CHECK(tape.stage_output_count(TapeLayout::kPositionStage) == layout.position_output_count());
  CHECK(tape.stage_output_count(TapeLayout::kAccelerationStage) == n);
  CHECK(tape.stage_output_count(TapeLayout::kPointStage) == layout.point_output_count());

  // Inputs at a closed-form position of the open branch.
  const kinema_unit::FourBar four_bar;
  const double t2 = 40 * kDeg, w2 = 10.0, al2 = 3.0;
  const double t3 = four_bar.theta3(t2), t4 = four_bar.theta4(t2);
  const double w3 = four_bar.omega3(t2, w2), w4 = four_bar.omega4(t2, w2);
  const double al3 = 0.7, al4 = -1.3;  // any values: gamma and the points are checked against GiNaC with the same
  std::vector<double> registers = tape.make_workspace();
  for (std::size_t p = 0; p < s.parameters.size(); ++p) registers[layout.parameter(p)] = s.parameters[p].value;
  registers[layout.input()] = t2;
  registers[layout.rate()] = w2;
  registers[layout.second_rate()] = al2;
  registers[layout.q(0)] = t3;
  registers[layout.q(1)] = t4;
  registers[layout.qd(0)] = w3;
  registers[layout.qd(1)] = w4;
  registers[layout.qdd(0)] = al3;
  registers[layout.qdd(1)] = al4;
  GiNaC::exmap values;
  for (const auto& p : s.parameters) values[p.symbol] = p.value;
  values[s.input.symbol] = t2;
  values[s.input.rate] = w2;
  values[s.input.second_rate] = al2;
  const double q[] = {t3, t4}, qd[] = {w3, w4}, qdd[] = {al3, al4};
  for (std::size_t i = 0; i < n; ++i) {
    values[s.unknowns[i].symbol] = q[i];
    values[s.unknowns[i].rate] = qd[i];
    values[s.unknowns[i].second_rate] = qdd[i];
  }

  std::vector<double> position(layout.position_output_count());
  tape.evaluate_stage(TapeLayout::kPositionStage, registers, position.data());
  for (std::size_t i = 0; i < n; ++i) {
    CAPTURE(i);
    CHECK(std::fabs(position[layout.phi(i)]) < 1e-15);  // closed: the loop's gap is at rounding level (m)
    CHECK(position[layout.phi_theta(i)] ==
          doctest::Approx(kinema_unit::numeric_value(d.input_jacobian(i, 0), values)).epsilon(1e-13));
    for (std::size_t j = 0; j < n; ++j) {
      CAPTURE(j);
      CHECK(position[layout.phi_q(i, j)] ==
            doctest::Approx(kinema_unit::numeric_value(d.jacobian(i, j), values)).epsilon(1e-13));
    }
  }
  // Phi_q by hand: [-b sin t3, c sin t4; b cos t3, -c cos t4] (column-major in the outputs).
  CHECK(position[layout.phi_q(0, 0)] == doctest::Approx(-0.12 * std::sin(t3)).epsilon(1e-13));
  CHECK(position[layout.phi_q(0, 1)] == doctest::Approx(0.08 * std::sin(t4)).epsilon(1e-13));
  CHECK(position[layout.phi_q(1, 0)] == doctest::Approx(0.12 * std::cos(t3)).epsilon(1e-13));
  CHECK(position[layout.phi_q(1, 1)] == doctest::Approx(-0.08 * std::cos(t4)).epsilon(1e-13));
  // The closed-form rates solve the velocity equations: Phi_q qd = -Phi_theta w2.
  for (std::size_t i = 0; i < n; ++i) {
    const double lhs = position[layout.phi_q(i, 0)] * w3 + position[layout.phi_q(i, 1)] * w4;
    CHECK(lhs == doctest::Approx(-position[layout.phi_theta(i)] * w2).epsilon(1e-12));
  }

  std::vector<double> gamma(n);
  tape.evaluate_stage(TapeLayout::kAccelerationStage, registers, gamma.data());
  for (std::size_t i = 0; i < n; ++i)
    CHECK(gamma[i] == doctest::Approx(kinema_unit::numeric_value(d.acceleration_rhs[i], values)).epsilon(1e-12));

  std::vector<double> points(layout.point_output_count());
  tape.evaluate_stage(TapeLayout::kPointStage, registers, points.data());
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    CAPTURE(s.points[p].name);
    const double* v = points.data() + layout.point_output(p);
    for (std::size_t c = 0; c < 2; ++c) {
      CHECK(v[c] == doctest::Approx(kinema_unit::numeric_value(s.points[p].position[c], values)).epsilon(1e-13));
      CHECK(v[2 + c] == doctest::Approx(kinema_unit::numeric_value(d.points[p].velocity[c], values)).epsilon(1e-12));
      CHECK(v[4 + c] ==
            doctest::Approx(kinema_unit::numeric_value(d.points[p].acceleration[c], values)).epsilon(1e-12));
    }
  }
  // B (point 1) is where the rocker ends: d + c e^{i t4}, moving at c w4 across the rocker.
  const double* b = points.data() + layout.point_output(1);
  CHECK(b[0] == doctest::Approx(0.1 + 0.08 * std::cos(t4)).epsilon(1e-14));
  CHECK(b[1] == doctest::Approx(0.08 * std::sin(t4)).epsilon(1e-14));
  CHECK(b[2] == doctest::Approx(-0.08 * std::sin(t4) * w4).epsilon(1e-12));
  CHECK(b[3] == doctest::Approx(0.08 * std::cos(t4) * w4).epsilon(1e-12));
}

TEST_CASE("engine/numeric/tape_layout: 2-D points of a two-loop system, parameters in file order") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml"));
  const TapeLayout& layout = model.kinematics.layout();
  CHECK(layout.unknown_count == 4);
  CHECK(layout.parameter_count == 8);
  CHECK(layout.point_dimensions.size() == 4);
  CHECK(layout.point_output_count() == 4 * 6);
  CHECK(model.kinematics.evaluator().input_count() == 8 + 3 + 12);
  // The parameter registers hold the file's values, in file order.
  for (std::size_t p = 0; p < layout.parameter_count; ++p)
    CHECK(model.kinematics.parameter_values()[layout.parameter(p)] == model.system.parameters[p].value);
  // Rows of Phi belong to the groups the equations say.
  for (std::size_t row = 0; row < 4; ++row) CHECK(model.kinematics.equation_group(row) == row / 2);
}
