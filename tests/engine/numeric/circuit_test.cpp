// A mechanism followed through its toggles (engine/numeric/circuit): the triple rocker's
// circuit closes after two toggles, each row on its assembly, with rates that finite
// differences of the closed-form positions confirm and loops that close on every row;
// a crank's circuit is one turn, the same rows as a sweep.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "engine/numeric/circuit.hpp"
#include "engine/numeric/sweep.hpp"
#include "engine/numeric/dyad_positions.hpp"

#include "tests/test_support.hpp"

namespace {

using kinema::Circuit;
using kinema::CircuitSettings;
using kinema::MotionTable;
using kinema::Status;

constexpr double kDegree = M_PI / 180;

CircuitSettings one_degree(const kinema::Model& model) {
  CircuitSettings settings;
  settings.start = model.system.input.values.front();
  settings.step = kDegree;
  settings.rate = model.system.input.rate_value;
  settings.second_rate = 3.0;  // a second rate too, so that the acceleration's input terms are checked
  settings.max_rows = 100000;
  return settings;
}

// The unknowns placed in closed form at x on a row's signs (the independent position
// solution the finite differences are taken of).
Eigen::VectorXd placed(const kinema::SolvingPlan& frames, double x, const std::vector<int>& signs,
                       const Eigen::VectorXd& near) {
  std::vector<kinema::BodyPose> poses;
  REQUIRE(kinema::place_dyads(frames, x, poses, &signs) == frames.dyads.size());
  Eigen::VectorXd q = near;
  kinema::unknowns_from_poses(frames, poses, q.data());
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] += 2 * M_PI * std::round((near[i] - q[i]) / (2 * M_PI));
  return q;
}

std::vector<int> row_signs(const MotionTable& table, std::size_t row, std::size_t dyads) {
  std::vector<int> signs;
  for (std::size_t k = 0; k < dyads; ++k) signs.push_back(table.assembly_sign(row, k));
  return signs;
}

}  // namespace

TEST_CASE("circuit: the triple rocker is followed through both toggles as one closed motion") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml"));
  const kinema::SolvingPlan& frames = *model.kinematics.closed_form();
  const CircuitSettings settings = one_degree(model);
  const Circuit circuit = kinema::solve_circuit(model.kinematics, settings);
  REQUIRE(circuit.stop == Circuit::Stop::closed);
  CHECK(circuit.toggles == 2);
  const MotionTable& t = circuit.table;
  REQUIRE(t.is_circuit());
  const std::size_t n = t.size();
  // The toggles where B, C, D fold into line (BD = BC - CD): cos phi = 0.9125.
  const double toggle = std::acos(0.9125);
  std::vector<double> toggles;
  for (std::size_t r = 0; r < n; ++r) {
    if (t.failure(r).kind != kinema::Failure::Kind::circuit_toggle) continue;
    CHECK(t.status(r) == Status::singular);
    CHECK(t.failure(r).group == 0);
    toggles.push_back(t.input(r));
  }
  REQUIRE(toggles.size() == 2);
  CHECK(toggles[0] == doctest::Approx(2 * M_PI - toggle).epsilon(1e-12));
  CHECK(toggles[1] == doctest::Approx(toggle).epsilon(1e-12));
  // Up from 90 deg to the first toggle, down to the second, up again to 90 deg: every
  // degree of the swing twice, once on each assembly.
  const std::size_t swing = static_cast<std::size_t>(std::floor((2 * M_PI - toggle) / kDegree + 1e-9)) -
                            static_cast<std::size_t>(std::ceil(toggle / kDegree - 1e-9)) + 1;
  CHECK(n == 2 * swing + 2 + 1);
  CHECK(t.input(0) == t.input(n - 1));
  for (Eigen::Index i = 0; i < t.q(0).size(); ++i) CHECK(t.q(n - 1)[i] == doctest::Approx(t.q(0)[i]).epsilon(1e-12));
  int sign_changes = 0, previous_sign = t.assembly_sign(0, 0);
  double largest_jump = 0;
  const std::size_t P = 2;  // points: B, C, P
  for (std::size_t r = 0; r < n; ++r) {
    CAPTURE(r);
    REQUIRE(t.status(r) != Status::unassembled);
    CHECK(t.loop_residual(r) < 1e-12 * model.kinematics.length_scale());
    if (t.assembly_sign(r, 0) != previous_sign) ++sign_changes;
    previous_sign = t.assembly_sign(r, 0);
    if (r + 1 < n) {
      // The input moves the way its rate says (the toggle row already moves on the way out).
      CHECK((t.input(r + 1) - t.input(r)) * t.input_rate(r) > 0);
      // One continuous motion: the coupler point never jumps to the other assembly
      // (which is tens of mm away), not even at a toggle.
      if (t.status(r) == Status::ok && t.status(r + 1) == Status::ok) {
        const auto a = t.point(r, P), b = t.point(r + 1, P);
        largest_jump = std::max(largest_jump, std::hypot(a.position[0] - b.position[0], a.position[1] - b.position[1]));
      }
    }
    if (t.status(r) != Status::ok) continue;
    // The rows are the closed-form positions on the row's assembly, and their rates what
    // finite differences of those positions give (dq/dphi * omega, d2q/dphi2 * omega^2 + dq/dphi * alpha).
    const double x = t.input(r), h = 1e-4, rate = t.input_rate(r), second_rate = t.input_second_rate(r);
    CHECK(std::fabs(rate) == doctest::Approx(std::fabs(settings.rate)));
    CHECK(second_rate == doctest::Approx(settings.second_rate * (rate > 0 ? 1 : -1) * (settings.rate > 0 ? 1 : -1)));
    const std::vector<int> signs = row_signs(t, r, frames.dyads.size());
    const Eigen::VectorXd q = t.q(r);
    if (std::fabs(x - toggles[0]) < 2 * h || std::fabs(x - toggles[1]) < 2 * h) continue;
    const Eigen::VectorXd back = placed(frames, x - h, signs, q), ahead = placed(frames, x + h, signs, q);
    const Eigen::VectorXd at = placed(frames, x, signs, q);
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      CHECK(at[i] == doctest::Approx(q[i]).epsilon(1e-10));
      const double slope = (ahead[i] - back[i]) / (2 * h), curvature = (ahead[i] - 2 * at[i] + back[i]) / (h * h);
      const double qd = slope * rate, qdd = curvature * rate * rate + slope * second_rate;
      const double scale = 1 + std::fabs(qd);
      CHECK(t.qd(r)[i] == doctest::Approx(qd).epsilon(1e-5 * scale).scale(1));
      CHECK(t.qdd(r)[i] == doctest::Approx(qdd).epsilon(1e-3).scale(1e-3 * (1 + std::fabs(qdd))));
    }
  }
  CHECK(sign_changes == 2);  // after each toggle
  // 1 deg of the input moves P at most a few mm, even next to a toggle (sqrt-like there).
  CHECK(largest_jump < 6e-3);
}

TEST_CASE("circuit: a crank's circuit is one turn without toggles, the rows of the sweep") {
  for (const std::string name : {"problem_4_4_joints.toml", "problem_4_1_parallelogram.toml"}) {
    CAPTURE(name);
    const bool parallelogram = name == "problem_4_1_parallelogram.toml";
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    CircuitSettings settings = one_degree(model);
    settings.second_rate = model.system.input.second_rate_value;
    const Circuit circuit = kinema::solve_circuit(model.kinematics, settings);
    REQUIRE(circuit.stop == Circuit::Stop::closed);
    CHECK(circuit.toggles == 0);
    const MotionTable& t = circuit.table;
    REQUIRE(t.size() == 361);
    std::vector<double> inputs;
    for (std::size_t r = 0; r < t.size(); ++r) inputs.push_back(settings.start + r * kDegree * (settings.rate < 0 ? -1 : 1));
    inputs.back() = t.input(t.size() - 1);
    CHECK(inputs.back() == doctest::Approx(settings.start + 2 * M_PI * (settings.rate < 0 ? -1 : 1)));
    const MotionTable sweep = kinema::solve_motion(model, inputs);
    for (std::size_t r = 0; r < t.size(); ++r) {
      CAPTURE(r);
      CHECK(t.input(r) == doctest::Approx(inputs[r]).epsilon(1e-14));
      CHECK(t.status(r) == sweep.status(r));
      // The six-bar keeps its assembly; the parallelogram stays a parallelogram (its
      // coupler BC parallel to AD) through its change points, where the signs change.
      if (!parallelogram)
        for (std::size_t k = 0; k < 2; ++k) CHECK(t.assembly_sign(r, k) == t.assembly_sign(0, k));
      if (parallelogram) CHECK(std::remainder(t.q(r)[0], 2 * M_PI) == doctest::Approx(0).scale(1).epsilon(1e-7));
      if (sweep.status(r) == Status::unassembled) continue;
      // At a change point (singular) the position is known to the square root of rounding.
      const double tolerance = sweep.status(r) == Status::ok ? 1e-9 : 1e-7;
      for (Eigen::Index i = 0; i < t.q(r).size(); ++i)
        CHECK(t.q(r)[i] == doctest::Approx(sweep.q(r)[i]).epsilon(tolerance).scale(1));
      if (sweep.status(r) != Status::ok) continue;
      for (Eigen::Index i = 0; i < t.q(r).size(); ++i) CHECK(t.qd(r)[i] == doctest::Approx(sweep.qd(r)[i]).epsilon(1e-9));
    }
  }
}

TEST_CASE("circuit: a start that cannot close, and a step too small for the row limit, stop with their reason") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml"));
  CircuitSettings settings = one_degree(model);
  settings.start = 0;  // B, C, D cannot close at phi = 0: beyond the toggles
  Circuit circuit = kinema::solve_circuit(model.kinematics, settings);
  CHECK(circuit.stop == Circuit::Stop::start_open);
  CHECK(circuit.dyad == 0);
  CHECK(circuit.table.empty());
  settings = one_degree(model);
  settings.max_rows = 100;
  circuit = kinema::solve_circuit(model.kinematics, settings);
  CHECK(circuit.stop == Circuit::Stop::too_many_rows);
  CHECK(circuit.table.empty());
}

namespace {

// Row r of `coarse` is a row of `fine` (the same input, direction, assembly and position):
// a coarse grid is a subset of a fine one's rows, toggles included.
void check_rows_of(const MotionTable& coarse, const MotionTable& fine, std::size_t dyads) {
  for (std::size_t r = 0; r < coarse.size(); ++r) {
    CAPTURE(r);
    CAPTURE(coarse.input(r) * 180 / M_PI);
    bool found = false;
    for (std::size_t f = 0; f < fine.size() && !found; ++f) {
      if (std::fabs(fine.input(f) - coarse.input(r)) > 1e-9 || fine.input_rate(f) != coarse.input_rate(r) ||
          fine.status(f) != coarse.status(r) || row_signs(fine, f, dyads) != row_signs(coarse, r, dyads))
        continue;
      found = true;
      for (Eigen::Index i = 0; i < coarse.q(r).size(); ++i)
        if (std::fabs(std::remainder(fine.q(f)[i] - coarse.q(r)[i], 2 * M_PI)) > 1e-9) found = false;  // angles to whole turns
    }
    CHECK(found);
  }
}

}  // namespace

// Session 30's hostile-input review: a step of 60 deg or more jumped over the range
// where the triple rocker cannot close (a "full turn" of two rows); 40 or 13 deg took a
// far position's assembly from a straight-line guess (wrong numbers, status ok); 30 deg
// never closed. Between rows the walk now takes substeps of at most 2 deg.
TEST_CASE("circuit: a coarse step gives rows of the one-degree circuit, toggles included") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml"));
  const std::size_t dyads = model.kinematics.closed_form()->dyads.size();
  const CircuitSettings fine_settings = one_degree(model);
  const Circuit fine = kinema::solve_circuit(model.kinematics, fine_settings);
  REQUIRE(fine.stop == Circuit::Stop::closed);
  for (const double degrees : {7.0, 13.0, 30.0, 40.0, 60.0, 120.0, 400.0, 1e9}) {
    CAPTURE(degrees);
    CircuitSettings settings = fine_settings;
    settings.step = degrees * kDegree;
    const Circuit coarse = kinema::solve_circuit(model.kinematics, settings);
    REQUIRE(coarse.stop == Circuit::Stop::closed);
    CHECK(coarse.toggles == 2);
    check_rows_of(coarse.table, fine.table, dyads);
    // Start, the grid values of the swing each way, the two toggles, the start again.
    CHECK(coarse.table.input(coarse.table.size() - 1) == coarse.table.input(0));
  }
}

// A start next to a toggle, or exactly at one (the toggle's value as printed), closes
// after the two toggles: the row beside the start took its assembly from a line through
// two positions a hair apart, and a start at the toggle was never passed again.
TEST_CASE("circuit: a start beside or at a toggle closes after one swing each way") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml"));
  const double toggle = std::acos(0.9125);
  for (const double start : {2 * M_PI - toggle - 1e-4 * kDegree, 2 * M_PI - toggle - 3e-3 * kDegree,
                             toggle + 1e-3 * kDegree, 2 * M_PI - toggle, toggle}) {
    for (const double degrees : {1.0, 30.0}) {
      CAPTURE(start * 180 / M_PI);
      CAPTURE(degrees);
      CircuitSettings settings = one_degree(model);
      settings.start = start;
      settings.step = degrees * kDegree;
      const Circuit circuit = kinema::solve_circuit(model.kinematics, settings);
      REQUIRE(circuit.stop == Circuit::Stop::closed);
      CHECK(circuit.toggles == 2);
      // Every degree (or 30) of the swing once each way, not twice.
      CHECK(circuit.table.size() <= 2 * static_cast<std::size_t>((2 * M_PI - 2 * toggle) / settings.step) + 6);
    }
  }
}
