// For every sample: the compiled rates and second rates equal central finite
// differences of the numeric position solution over a whole sweep (its
// feasible part), and the loops close.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/model.hpp"
#include "tests/test_support.hpp"

namespace {

using kinema::MotionState;
using kinema::Status;

struct SweepCase {
  const char* sample;
  double start, stop, step;  // SI
};

void check_against_finite_differences(const SweepCase& c) {
  const kinema::Model model = kinema::load_model(kinema_test::sample(c.sample));
  const kinema::Kinematics& k = model.kinematics;
  std::vector<double> inputs;
  for (double v = c.start; v <= c.stop + 1e-12; v += c.step) inputs.push_back(v);
  const double rate = model.system.input.rate_value;
  const double second_rate = model.system.input.second_rate_value;
  const auto states = kinema::solve_motion(model, inputs);
  const bool angle_input = model.system.input.dimension == kinema::Dimension::angle;
  const double h = angle_input ? 1e-4 : 1e-5 * k.length_scale();
  kinema::Workspace workspace(k);
  int checked = 0;
  for (const MotionState& s : states) {
    if (s.status != Status::ok || s.reciprocal_condition < 1e-2) continue;
    CAPTURE(s.input);
    CHECK(s.loop_residual < 1e-12 * k.length_scale());
    Eigen::VectorXd plus = s.q, minus = s.q;
    REQUIRE(workspace.solve_position(s.input + h, plus));
    REQUIRE(workspace.solve_position(s.input - h, minus));
    const Eigen::VectorXd first = (plus - minus) / (2 * h);
    const Eigen::VectorXd second = (plus - 2 * s.q + minus) / (h * h);
    for (Eigen::Index i = 0; i < s.q.size(); ++i) {
      CAPTURE(model.system.unknowns[i].name);
      const double expected_rate = first[i] * rate;
      const double expected_second = second[i] * rate * rate + first[i] * second_rate;
      CHECK(std::fabs(s.qd[i] - expected_rate) <= 1e-6 * (std::fabs(rate) + std::fabs(expected_rate)));
      CHECK(std::fabs(s.qdd[i] - expected_second) <=
            1e-4 * (rate * rate + std::fabs(second_rate) + std::fabs(expected_second)));
    }
    // Points: velocity and acceleration against differences of their positions.
    const MotionState at_plus = workspace.motion(s.input + h, rate, second_rate, plus);
    const MotionState at_minus = workspace.motion(s.input - h, rate, second_rate, minus);
    for (std::size_t p = 0; p < s.points.size(); ++p) {
      CAPTURE(model.system.points[p].name);
      const auto &pp = at_plus.points[p], &p0 = s.points[p], &pm = at_minus.points[p];
      const double scale = k.length_scale() * (std::fabs(rate) + std::fabs(second_rate) + rate * rate);
      REQUIRE(p0.dimension == 2);
      for (std::size_t c = 0; c < p0.dimension; ++c) {
        const double d = (pp.position[c] - pm.position[c]) / (2 * h);
        const double dd = (pp.position[c] - 2 * p0.position[c] + pm.position[c]) / (h * h);
        const double v = d * rate, a = dd * rate * rate + d * second_rate;
        CHECK(std::fabs(p0.velocity[c] - v) <= 1e-6 * (scale + std::fabs(v)));
        CHECK(std::fabs(p0.acceleration[c] - a) <= 1e-4 * (scale + std::fabs(a)));
      }
    }
    ++checked;
  }
  // The sweep must really have exercised the formulas.
  CHECK(checked >= 10);
}

constexpr double deg = M_PI / 180.0;

}  // namespace

TEST_CASE("finite differences: four-bar over a full revolution") {
  check_against_finite_differences({"four_bar.toml", 0, 360 * deg, 5 * deg});
}
TEST_CASE("finite differences: slider-crank over a full revolution") {
  check_against_finite_differences({"slider_crank.toml", 0, 360 * deg, 5 * deg});
}
TEST_CASE("finite differences: piston-driven crank between its dead centres") {
  check_against_finite_differences({"piston_driven_crank.toml", 0.11, 0.19, 0.002});
}
TEST_CASE("finite differences: Example 4.1 R-TRR over a revolution") {
  check_against_finite_differences({"example_4_1_r_trr.toml", 0, 360 * deg, 5 * deg});
}
TEST_CASE("finite differences: Example 4.2 R-RTR-RRT over a revolution") {
  check_against_finite_differences({"example_4_2_r_rtr_rrt.toml", 0, 360 * deg, 5 * deg});
}
TEST_CASE("finite differences: Problem 4.4 six-bar over a revolution") {
  check_against_finite_differences({"problem_4_4_six_bar.toml", 0, 360 * deg, 5 * deg});
}
TEST_CASE("finite differences: Problem 3.22 over a revolution") {
  check_against_finite_differences({"problem_3_22_six_bar_sliders.toml", -180 * deg, 180 * deg, 5 * deg});
}

// Joints and links (positions placed dyad by dyad): every link's angle and every joint.
TEST_CASE("finite differences: every joints-and-links sample over a revolution") {
  for (const char* sample : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                             "problem_3_22_joints.toml", "problem_4_1_parallelogram.toml",
                             "problem_4_1_antiparallelogram.toml"}) {
    CAPTURE(sample);
    check_against_finite_differences({sample, 0, 360 * deg, 5 * deg});
  }
}
