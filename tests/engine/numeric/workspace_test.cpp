// engine/numeric/workspace: one input value at a time. Newton from the
// guesses against the closed-form four-bar, rates and second rates against
// the textbook formulas and finite differences of them, singular positions
// (a triple rocker's toggle, the piston-driven crank's dead centre), the loop
// that stays open, branch keeping in predict_and_correct and continue_to.
#include <doctest/doctest.h>

#include <complex>

#include <cmath>

#include "engine/numeric/workspace.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::Failure;
using kinema::MotionState;
using kinema::Status;
using kinema::Workspace;
using kinema_unit::kDeg;
using kinema_unit::same_angle;

namespace {

const kinema_unit::FourBar kFourBar;

// A non-Grashof four-bar (a, b, c, d = 100, 50, 90, 60 mm): assembles for |theta2| <= 120 deg;
// at theta2 = 0 the coupler and rocker are folded on each other (toggle, theta3 = theta4 = 0).
const char* const kTripleRocker = R"toml(title = "triple rocker"
[parameters]
a = "100 mm"
b = "50 mm"
c = "90 mm"
d = "60 mm"
[input]
name = "theta2"
rate = "1 rad/s"
[unknowns]
theta3 = "80 deg"
theta4 = "100 deg"
[loops]
ABCD = "a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d"
)toml";

// The sample four-bar and a dyad of two 30 mm links that must reach 500 mm: never closes.
std::string with_far_loop(bool far_first) {
  const std::string four_bar = "ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d\"\n";
  const std::string far = "Far = \"e*exp(I*theta5) + f*exp(I*theta6) - g\"\n";
  return std::string(R"toml(title = "four-bar and a dyad that cannot reach"
[parameters]
a = "40 mm"
b = "120 mm"
c = "80 mm"
d = "100 mm"
e = "30 mm"
f = "30 mm"
g = "500 mm"
[input]
name = "theta2"
rate = "10 rad/s"
[unknowns]
theta3 = "20 deg"
theta4 = "80 deg"
theta5 = "10 deg"
theta6 = "60 deg"
[loops]
)toml") + (far_first ? far + four_bar : four_bar + far);
}

}  // namespace

TEST_CASE("engine/numeric/workspace: Newton from the guesses lands on the closed-form open branch") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  Workspace workspace(model);
  for (double degrees : {40.0, 10.0, 70.0}) {
    CAPTURE(degrees);
    const double t2 = degrees * kDeg;
    Eigen::VectorXd q = model.kinematics.guess();
    CHECK(q[0] == doctest::Approx(20 * kDeg));
    std::size_t worst = 99;
    double residual = 1;
    REQUIRE(workspace.solve_position(t2, q, &worst, &residual));
    CHECK(same_angle(q[0], kFourBar.theta3(t2), 1e-12));
    CHECK(same_angle(q[1], kFourBar.theta4(t2), 1e-12));
    CHECK(residual <= 1e-13 * model.kinematics.length_scale());
    CHECK(worst == 0);  // the only group
  }
  // Already solved: stays where it is.
  Eigen::VectorXd q(2);
  q << kFourBar.theta3(0.5), kFourBar.theta4(0.5);
  const Eigen::VectorXd solved = q;
  REQUIRE(workspace.solve_position(0.5, q));
  CHECK((q - solved).norm() < 1e-14);
}

TEST_CASE("engine/numeric/workspace: motion: textbook rates, second rates by finite differences, points") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  Workspace workspace(model);
  const double t2 = 40 * kDeg, w2 = 10.0, al2 = 3.0;
  Eigen::VectorXd q = model.kinematics.guess();
  REQUIRE(workspace.solve_position(t2, q));
  const MotionState s = workspace.motion(t2, w2, al2, q);
  REQUIRE(s.status == Status::ok);
  CHECK(s.failure.kind == Failure::Kind::none);
  CHECK(s.input == t2);
  CHECK(s.input_rate == w2);
  CHECK(s.input_second_rate == al2);
  CHECK(s.q == q);
  CHECK(s.loop_residual < 1e-15);
  CHECK(s.reciprocal_condition > 1e-5);
  CHECK(s.reciprocal_condition <= 1.0);
  CHECK(s.qd[0] == doctest::Approx(kFourBar.omega3(t2, w2)).epsilon(1e-12));
  CHECK(s.qd[1] == doctest::Approx(kFourBar.omega4(t2, w2)).epsilon(1e-12));

  // qdd = w2^2 d(omega/w2)/dtheta2 + al2 (omega/w2), the derivative by central differences of the closed form.
  const double h = 1e-5;
  const double d3 = (kFourBar.omega3(t2 + h, 1.0) - kFourBar.omega3(t2 - h, 1.0)) / (2 * h);
  const double d4 = (kFourBar.omega4(t2 + h, 1.0) - kFourBar.omega4(t2 - h, 1.0)) / (2 * h);
  CHECK(s.qdd[0] == doctest::Approx(w2 * w2 * d3 + al2 * kFourBar.omega3(t2, 1.0)).epsilon(1e-8));
  CHECK(s.qdd[1] == doctest::Approx(w2 * w2 * d4 + al2 * kFourBar.omega4(t2, 1.0)).epsilon(1e-8));

  // Points A = a e^{i t2}, B = d + c e^{i t4}, P = A + p e^{i (t3 + delta)}.
  REQUIRE(s.points.size() == 3);
  const double a = 0.04, c = 0.08, d = 0.1, p = 0.06, delta = 30 * kDeg;
  const auto& A = s.points[0];
  CHECK(A.dimension == 2);
  CHECK(A.position[0] == doctest::Approx(a * std::cos(t2)).epsilon(1e-14));
  CHECK(A.velocity[0] == doctest::Approx(-a * w2 * std::sin(t2)).epsilon(1e-13));
  CHECK(A.velocity[1] == doctest::Approx(a * w2 * std::cos(t2)).epsilon(1e-13));
  CHECK(A.acceleration[0] == doctest::Approx(-a * al2 * std::sin(t2) - a * w2 * w2 * std::cos(t2)).epsilon(1e-13));
  CHECK(A.acceleration[1] == doctest::Approx(a * al2 * std::cos(t2) - a * w2 * w2 * std::sin(t2)).epsilon(1e-13));
  CHECK(A.speed() == doctest::Approx(a * w2).epsilon(1e-13));
  const double t4 = s.q[1], w4 = s.qd[1], al4 = s.qdd[1];
  const auto& B = s.points[1];
  CHECK(B.position[0] == doctest::Approx(d + c * std::cos(t4)).epsilon(1e-14));
  CHECK(B.velocity[1] == doctest::Approx(c * w4 * std::cos(t4)).epsilon(1e-12));
  CHECK(B.acceleration[0] == doctest::Approx(-c * al4 * std::sin(t4) - c * w4 * w4 * std::cos(t4)).epsilon(1e-12));
  const auto& P = s.points[2];
  CHECK(P.position[1] == doctest::Approx(a * std::sin(t2) + p * std::sin(s.q[0] + delta)).epsilon(1e-14));

  // sensitivity: dq/dtheta2 = qd / w2.
  Eigen::VectorXd dq;
  REQUIRE(workspace.sensitivity(t2, q, dq));
  CHECK(dq[0] == doctest::Approx(s.qd[0] / w2).epsilon(1e-12));
  CHECK(dq[1] == doctest::Approx(s.qd[1] / w2).epsilon(1e-12));

  // motion_into reuses a state: the same numbers.
  MotionState reused = workspace.motion(0.3, 1, 0, q);  // any other content first
  workspace.motion_into(t2, w2, al2, q, reused);
  CHECK(reused.qdd == s.qdd);
  CHECK(reused.points[2].acceleration[0] == s.points[2].acceleration[0]);
}

TEST_CASE("engine/numeric/workspace: singular at a triple rocker's toggle and at the piston's dead centre") {
  // Triple rocker at theta2 = 0: theta3 = theta4 = 0 closes the loop exactly (100 + 50 - 90 - 60 = 0).
  const kinema::Model rocker = kinema_unit::model_from_text(kTripleRocker, "rocker.toml");
  Workspace rocker_workspace(rocker);
  const Eigen::VectorXd folded = Eigen::VectorXd::Zero(2);
  const MotionState toggle = rocker_workspace.motion(0.0, 1.0, 0.0, folded);
  CHECK(toggle.status == Status::singular);
  CHECK(toggle.failure.kind == Failure::Kind::singular_jacobian);
  CHECK(toggle.reciprocal_condition < 1e-5);
  CHECK(toggle.loop_residual < 1e-16);  // the position itself is fine
  CHECK(toggle.q == folded);
  CHECK(toggle.qd.size() == 0);
  CHECK(toggle.points.empty());
  Eigen::VectorXd dq;
  CHECK_FALSE(rocker_workspace.sensitivity(0.0, folded, dq));
  // Away from the toggle the same rocker is regular.
  Eigen::VectorXd q = rocker.kinematics.guess();
  REQUIRE(rocker_workspace.solve_position(90 * kDeg, q));
  CHECK(rocker_workspace.motion(90 * kDeg, 1.0, 0.0, q).status == Status::ok);

  // Piston-driven crank at x = a + b = 200 mm: crank and rod in line (theta2 = theta3 = 0).
  const kinema::Model piston = kinema::load_model(kinema_test::sample("piston_driven_crank.toml"));
  Workspace piston_workspace(piston);
  const MotionState dead = piston_workspace.motion(0.2, -2.0, 5.0, folded);
  CHECK(dead.status == Status::singular);
  CHECK(dead.failure.kind == Failure::Kind::singular_jacobian);
  CHECK(dead.reciprocal_condition < 1e-5);
  // 10 mm before it: regular, and the crank turns.
  Eigen::VectorXd near = piston.kinematics.guess();
  REQUIRE(piston_workspace.solve_position(0.19, near));
  const MotionState before = piston_workspace.motion(0.19, -2.0, 5.0, near);
  CHECK(before.status == Status::ok);
  CHECK(std::isfinite(before.qd[0]));
  CHECK(piston_workspace.max_continuation_step() == doctest::Approx(0.01 * 0.15));
  CHECK(rocker_workspace.max_continuation_step() == doctest::Approx(2 * kDeg));
}

TEST_CASE("engine/numeric/workspace: solve_position names the loop that cannot close") {
  for (const bool far_first : {false, true}) {
    CAPTURE(far_first);
    const kinema::Model model = kinema_unit::model_from_text(with_far_loop(far_first), "far.toml");
    const std::size_t far_group = far_first ? 0 : 1;
    REQUIRE(model.system.groups[far_group].name == "Far");
    Workspace workspace(model);
    Eigen::VectorXd q = model.kinematics.guess();
    std::size_t worst = 99;
    double residual = 0;
    CHECK_FALSE(workspace.solve_position(40 * kDeg, q, &worst, &residual));
    CHECK(worst == far_group);
    // The gap is at least the 440 mm the links lack along x, spread over x and y at worst.
    CHECK(residual > 0.2);
    CHECK(q.allFinite());
  }
}

TEST_CASE("engine/numeric/workspace: predict_and_correct and continue_to keep the branch") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  Workspace workspace(model);
  const double t2 = 40 * kDeg;
  Eigen::VectorXd open(2);
  open << kFourBar.theta3(t2), kFourBar.theta4(t2);

  // A step of 2 deg predicted close to the solution: corrected onto it.
  const double before = t2 - 2 * kDeg;
  Eigen::VectorXd from(2);
  from << kFourBar.theta3(before), kFourBar.theta4(before);
  const int sign = workspace.jacobian_sign(before, from);
  CHECK(sign != 0);
  Eigen::VectorXd predicted = open + Eigen::Vector2d(0.001, -0.001);
  Eigen::VectorXd q = from;
  REQUIRE(workspace.predict_and_correct(before, t2, predicted, q, sign));
  CHECK((q - open).norm() < 1e-12);
  // A prediction 0.3 rad off: whatever Newton finds is not near it: refused, q unchanged.
  predicted = open + Eigen::Vector2d(0.3, 0.0);
  Eigen::VectorXd kept = from;
  CHECK_FALSE(workspace.predict_and_correct(before, t2, predicted, kept, sign));
  CHECK(kept == from);
  // Corrected onto the solution, but the correction is large beside the step predicted
  // (a step predicted to barely move): refused, as a step over a narrow gap is.
  kept = from;
  CHECK_FALSE(workspace.predict_and_correct(before, t2, from, kept, sign));
  // Open 2 deg before and crossed at t2 (C mirrored across BD): det Phi_q's sign differs,
  // and no change point lies between (the two assemblies stay apart): not a step on a branch.
  const std::complex<double> b_pin = std::polar(kFourBar.a, t2), d_pin(kFourBar.d, 0);
  const std::complex<double> c_pin = b_pin + std::polar(kFourBar.b, open[0]);
  const std::complex<double> along = (d_pin - b_pin) / std::abs(d_pin - b_pin);
  const std::complex<double> mirrored = b_pin + along * std::conj((c_pin - b_pin) / along);
  Eigen::VectorXd crossed(2);
  crossed << std::arg(mirrored - b_pin), std::arg(mirrored - d_pin);
  const int crossed_sign = workspace.jacobian_sign(t2, crossed);
  CHECK(crossed_sign == -sign);
  CHECK_FALSE(workspace.change_point_between(before, from, sign, t2, crossed, crossed_sign));

  // Half a turn in one call, on the open branch all the way.
  q = open;
  REQUIRE(workspace.continue_to(t2, t2 + M_PI, q, nullptr));
  CHECK(same_angle(q[0], kFourBar.theta3(t2 + M_PI), 1e-10));
  CHECK(same_angle(q[1], kFourBar.theta4(t2 + M_PI), 1e-10));
  // And backwards.
  REQUIRE(workspace.continue_to(t2 + M_PI, t2 - 0.5, q, nullptr));
  CHECK(same_angle(q[1], kFourBar.theta4(t2 - 0.5), 1e-10));

  // The triple rocker stops at its limit, 120 deg.
  const kinema::Model rocker = kinema_unit::model_from_text(kTripleRocker, "rocker.toml");
  Workspace rocker_workspace(rocker);
  Eigen::VectorXd r = rocker.kinematics.guess();
  REQUIRE(rocker_workspace.solve_position(90 * kDeg, r));
  double stuck = 0;
  CHECK_FALSE(rocker_workspace.continue_to(90 * kDeg, 180 * kDeg, r, &stuck));
  CHECK(stuck / kDeg == doctest::Approx(120).epsilon(0.005));
  CHECK(stuck <= 120 * kDeg + 1e-9);

  // advance from a solved state: the same as solving there from scratch.
  MotionState state = workspace.motion(t2, 10.0, 0.0, open);
  REQUIRE(workspace.advance(t2 + 0.5 * kDeg, 10.0, 0.0, state));
  CHECK(state.input == t2 + 0.5 * kDeg);
  CHECK(same_angle(state.q[0], kFourBar.theta3(t2 + 0.5 * kDeg), 1e-12));
  CHECK(state.qd[1] == doctest::Approx(kFourBar.omega4(t2 + 0.5 * kDeg, 10.0)).epsilon(1e-11));
}
