// engine/numeric/sweep: solve_sweep (and solve_motion, which calls it) turns what
// cannot be solved into rows with a status and a structured Failure: the
// group that stays open, where a branch stops, a row after a gap, a singular
// row; what can be solved matches the closed-form four-bar.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/numeric/sweep.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::Failure;
using kinema::MotionTable;
using kinema::Status;
using kinema::SweepSettings;
using kinema_unit::kDeg;
using kinema_unit::same_angle;

namespace {

// A triple rocker (assembles for |theta2| <= 120 deg).
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

// The sample four-bar (closes at every angle) and, driven by the same crank, the triple
// rocker as a second loop (group 1), which does not close beyond 120 deg.
const char* const kTwoLoops = R"toml(title = "four-bar and triple rocker on one crank"
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
)toml";

SweepSettings settings(double rate, double second_rate = 0.0) {
  SweepSettings s;
  s.rate = rate;
  s.second_rate = second_rate;
  return s;
}

std::vector<double> degrees(std::initializer_list<double> values) {
  std::vector<double> radians;
  for (double v : values) radians.push_back(v * kDeg);
  return radians;
}

}  // namespace

TEST_CASE("engine/numeric/sweep: the four-bar over a turn equals the closed form, SIMD blocks or not") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  std::vector<double> inputs;
  for (int i = 0; i <= 1800; ++i) inputs.push_back(40 * kDeg + i * 0.2 * kDeg);  // a turn in 0.2 deg steps
  const kinema_unit::FourBar four_bar;
  for (const bool simd : {true, false}) {
    CAPTURE(simd);
    SweepSettings s = settings(10.0, 2.0);
    s.simd = simd;
    const MotionTable table = kinema::solve_sweep(model.kinematics, inputs, s);
    REQUIRE(table.size() == inputs.size());
    CHECK(table.input_rate() == 10.0);
    CHECK(table.input_second_rate() == 2.0);
    // Most of a regular sweep goes 32 values at a time (the first rows one by one).
    if (simd) CHECK(table.batch_rows() >= inputs.size() / 2);
    if (!simd) CHECK(table.batch_rows() == 0);
    std::size_t not_ok = 0, noted = 0, moved = 0;
    double angle_error = 0, rate_error = 0;
    for (std::size_t r = 0; r < table.size(); ++r) {
      not_ok += table.status(r) != Status::ok;
      noted += table.failure(r).kind != Failure::Kind::none;
      const double t2 = table.input(r);
      moved += t2 != inputs[r];
      angle_error = std::max({angle_error, std::fabs(std::remainder(table.q(r)[0] - four_bar.theta3(t2), 2 * M_PI)),
                              std::fabs(std::remainder(table.q(r)[1] - four_bar.theta4(t2), 2 * M_PI))});
      rate_error = std::max(rate_error, std::fabs(table.qd(r)[1] - four_bar.omega4(t2, 10.0)));
    }
    CHECK(not_ok == 0);
    CHECK(noted == 0);
    CHECK(moved == 0);
    CHECK(angle_error < 1e-10);
    CHECK(rate_error < 1e-9);
  }
  CHECK(kinema::solve_sweep(model.kinematics, {}, settings(1.0)).empty());
}

TEST_CASE("engine/numeric/sweep: a value that cannot be assembled names the open group") {
  const kinema::Model model = kinema_unit::model_from_text(kTwoLoops, "two.toml");
  REQUIRE(model.system.groups.at(1).name == "Rocker");
  const MotionTable table = kinema::solve_sweep(model.kinematics, degrees({180, 90}), settings(10.0));
  REQUIRE(table.size() == 2);
  CHECK(table.status(0) == Status::unassembled);
  const Failure& f = table.failure(0);
  CHECK(f.kind == Failure::Kind::group_open);
  CHECK(f.group == 1);  // the rocker, not the four-bar
  CHECK(f.from_guesses);
  // |AD| = 160 mm against b2 + c2 = 140 mm: at least part of the 20 mm stays open.
  CHECK(f.residual > 0.005);
  CHECK(f.residual < 0.2);
  CHECK(table[0].q.size() == 0);
  // 90 deg closes from the guesses; nothing was solved before it, so there is no gap to resume after.
  CHECK(table.status(1) == Status::ok);
  CHECK(table.failure(1).kind == Failure::Kind::none);
  const kinema_unit::FourBar four_bar;
  CHECK(same_angle(table.q(1)[1], four_bar.theta4(90 * kDeg), 1e-10));

  // The single-loop rocker: the same, group 0.
  const kinema::Model rocker = kinema_unit::model_from_text(kTripleRocker, "rocker.toml");
  const MotionTable alone = kinema::solve_sweep(rocker.kinematics, degrees({180}), settings(1.0));
  CHECK(alone.failure(0).kind == Failure::Kind::group_open);
  CHECK(alone.failure(0).group == 0);
}

TEST_CASE("engine/numeric/sweep: the branch stops at the limit - rows after the gap say so") {
  const kinema::Model rocker = kinema_unit::model_from_text(kTripleRocker, "rocker.toml");
  const MotionTable table = kinema::solve_sweep(rocker.kinematics, degrees({90, 180, 200, 300, 310}), settings(1.0));
  REQUIRE(table.size() == 5);
  CHECK(table.status(0) == Status::ok);
  CHECK(table.failure(0).kind == Failure::Kind::none);

  // 180 deg cannot be reached from 90 deg: the motion stops at 120 deg.
  CHECK(table.status(1) == Status::unassembled);
  const Failure& stops = table.failure(1);
  CHECK(stops.kind == Failure::Kind::branch_stops);
  CHECK(stops.from == 90 * kDeg);
  CHECK(stops.stopped_at / kDeg == doctest::Approx(120).epsilon(0.005));

  // 200 deg, tried from the last assembled position (not the guesses): open.
  CHECK(table.status(2) == Status::unassembled);
  CHECK(table.failure(2).kind == Failure::Kind::group_open);
  CHECK_FALSE(table.failure(2).from_guesses);

  // 300 deg (= -60 deg) closes again: ok, with the note that the branch across the gap is not guaranteed ...
  CHECK(table.status(3) == Status::ok);
  CHECK(table.failure(3).kind == Failure::Kind::resumed_after_gap);
  CHECK(table[3].qd.size() == 2);
  // ... and the row after it is continued as usual.
  CHECK(table.status(4) == Status::ok);
  CHECK(table.failure(4).kind == Failure::Kind::none);
}

TEST_CASE("engine/numeric/sweep: the piston's dead centre is a singular row with its position") {
  const kinema::Model piston = kinema::load_model(kinema_test::sample("piston_driven_crank.toml"));
  const std::vector<double> inputs = {0.15, 0.16, 0.17, 0.18, 0.19, 0.20};
  const MotionTable table = kinema::solve_sweep(piston.kinematics, inputs, settings(-2.0, 5.0));
  REQUIRE(table.size() == 6);
  for (std::size_t r = 0; r < 5; ++r) CHECK(table.status(r) == Status::ok);
  CHECK(table.status(5) == Status::singular);
  CHECK(table.failure(5).kind == Failure::Kind::singular_jacobian);
  const kinema::MotionState dead = table[5];
  REQUIRE(dead.q.size() == 2);
  // Crank and rod in line: both angles ~0 (Newton at a singular point is only sqrt(eps) accurate).
  CHECK(std::fabs(std::remainder(dead.q[0], 2 * M_PI)) < 1e-5);
  CHECK(std::fabs(std::remainder(dead.q[1], 2 * M_PI)) < 1e-5);
  CHECK(dead.qd.size() == 0);
  CHECK(dead.points.empty());
}

TEST_CASE("engine/numeric/sweep: solve_motion takes the model's rates unless told otherwise") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const MotionTable by_default = kinema::solve_motion(model, degrees({40, 41}));
  CHECK(by_default.input_rate() == model.system.input.rate_value);
  CHECK(by_default.input_second_rate() == model.system.input.second_rate_value);
  const MotionTable given = kinema::solve_motion(model, degrees({40, 41}), kinema_test::with_rates(-5.0, 1.0));
  CHECK(given.input_rate() == -5.0);
  CHECK(given.input_second_rate() == 1.0);
  // Rates scale with the input rate: omega3 at -5 rad/s is -1/2 of omega3 at 10 rad/s.
  CHECK(given.qd(0)[0] == doctest::Approx(-0.5 * by_default.qd(0)[0]).epsilon(1e-12));
  // The same rows as solve_sweep with the same settings.
  const MotionTable direct = kinema::solve_sweep(model.kinematics, degrees({40, 41}), settings(-5.0, 1.0));
  CHECK(direct.qdd(1)[1] == given.qdd(1)[1]);
}
