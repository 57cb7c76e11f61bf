// engine/numeric/dyad_positions: the closed-form, dyad-by-dyad positions of the joints-and-links
// samples equal the solved loops (Newton, continued from the sketch) at every value of
// a sweep, on the sketch's assembly signs; the other sign is the other assembly; a
// dyad that cannot close is named.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "engine/model.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "linkages/linkage_loops.hpp"
#include "engine/numeric/dyad_positions.hpp"
#include "readers/mechanism_file.hpp"
#include "linkages/vector_loop_file.hpp"
#include "tests/test_support.hpp"

namespace {

std::vector<double> closed_form(const kinema::SolvingPlan& frames, double input, std::size_t unknowns,
                                const std::vector<int>* signs = nullptr) {
  std::vector<kinema::BodyPose> poses;
  REQUIRE(kinema::place_dyads(frames, input, poses, signs) == frames.dyads.size());
  std::vector<double> q(unknowns);
  kinema::unknowns_from_poses(frames, poses, q.data());
  return q;
}

}  // namespace

TEST_CASE("engine/numeric/dyad_positions: the dyads' closed forms are the loops' solutions on the sketch's branch") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml"}) {
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    REQUIRE(model.system.plan);
    const kinema::SolvingPlan& frames = *model.system.plan;
    REQUIRE(frames.closed_form);
    const double start = model.system.input.values.at(0);
    std::vector<double> inputs;
    for (int k = 0; k <= 24; ++k) inputs.push_back(start + k * M_PI / 180);  // a 24 deg stretch from the file's value
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    for (std::size_t row = 0; row < inputs.size(); ++row) {
      CAPTURE(row);
      REQUIRE(table.status(row) == kinema::Status::ok);
      const std::vector<double> q = closed_form(frames, inputs[row], model.system.unknowns.size());
      for (std::size_t i = 0; i < q.size(); ++i) {
        CAPTURE(model.system.unknowns[i].name);
        const double solved = table.q(row)[Eigen::Index(i)];
        const double difference = model.system.unknowns[i].dimension == kinema::Dimension::angle
                                      ? std::remainder(q[i] - solved, 2 * M_PI)
                                      : q[i] - solved;
        CHECK(std::fabs(difference) < 1e-9);
      }
    }
  }
}

namespace {

// A triple rocker (non-Grashof: 30 + 70 > 40 + 38): the crank rocks between about
// -70.4 and 70.4 deg; C is drawn above the line BD.
const std::string kTripleRocker = R"(title = "triple rocker"
[parameters]
a = "40 mm"
b = "30 mm"
c = "38 mm"
[joints]
A = { ground = true, at = ["0 mm", "0 mm"] }
B = { at = ["40 mm", "0 mm"] }
C = { at = ["45.9333 mm", "29.4071 mm"] }
D = { ground = true, at = ["70 mm", "0 mm"] }
[links]
2 = { joints = ["A", "B"], length = "a" }
3 = { joints = ["B", "C"], length = "b" }
4 = { joints = ["D", "C"], length = "c" }
[driver]
link = "2"
value = "0 deg"
rate = "1 rad/s"
)";

double degrees(double d) { return d * M_PI / 180; }

// Which side of the line BD the joint C is on (the RRR dyad's assembly).
int side_of_c(const kinema::MotionTable& table, std::size_t row) {
  const auto b = table.point(row, 0).position, c = table.point(row, 1).position;
  const double dx = 0.070 - b[0], dy = -b[1];
  return (c[0] - b[0]) * dy - (c[1] - b[1]) * dx < 0 ? 1 : -1;
}

}  // namespace

TEST_CASE("engine/numeric/dyad_positions: a list goes the short way round, and a value where the dyad cannot close names it") {
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(kTripleRocker, "rocker.toml"));
  REQUIRE(model.kinematics.closed_form() != nullptr);
  REQUIRE(model.system.points.at(0).name == "B");
  // 300 deg is -60 deg: reached directly (continuation from 0 would run into the toggle at 70.4 deg).
  const kinema::MotionTable list = kinema::solve_motion(model, {0, degrees(300), degrees(-60), degrees(60)});
  for (std::size_t row = 0; row < 4; ++row) {
    CAPTURE(row);
    REQUIRE(list.status(row) == kinema::Status::ok);
    CHECK(side_of_c(list, row) == side_of_c(list, 0));
  }
  for (int k = 0; k < 2; ++k) CHECK(list.q(1)[k] == doctest::Approx(list.q(2)[k]).epsilon(1e-12));
  // The same mechanism as hand-written loops goes the short way too, to the same position.
  const kinema::Mechanism drawn = kinema::read_mechanism_text(kTripleRocker, "rocker.toml");
  const kinema::Model loops = kinema::make_model(kinema::read_mechanism_text(kinema_test::loops_file(drawn), "loops.toml"));
  const kinema::MotionTable by_loops = kinema::solve_motion(loops, {0, degrees(300)});
  REQUIRE(by_loops.status(1) == kinema::Status::ok);
  CHECK(by_loops.failure(1).kind == kinema::Failure::Kind::none);
  REQUIRE(loops.system.points.at(0).name == "B");
  REQUIRE(loops.system.points.at(1).name == "C");
  for (std::size_t row = 0; row < 2; ++row)
    for (std::size_t point = 0; point < 2; ++point)
      for (int axis = 0; axis < 2; ++axis)
        CHECK(by_loops.point(row, point).position[axis] ==
              doctest::Approx(list.point(row, point).position[axis]).epsilon(1e-9));

  const kinema::MotionTable beyond = kinema::solve_motion(model, {0, degrees(100)});
  REQUIRE(beyond.status(1) == kinema::Status::unassembled);
  CHECK(beyond.failure(1).kind == kinema::Failure::Kind::dyad_open);
  CHECK(kinema::describe_failure(model.system, degrees(100), beyond.failure(1)) ==
        "dyad 1 (RRR: links 3, 4; joints B, C, D) cannot close at theta2 = 100 deg: its links do not reach on the "
        "assembly of the sketch; choose another input value, or check the lengths");
}

TEST_CASE("engine/numeric/dyad_positions: across a gap the motion resumes on the sketch's assembly, and no ok row changes it") {
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(kTripleRocker, "rocker.toml"));
  std::vector<double> inputs;
  for (double d = -90; d <= 90; d += 0.5) inputs.push_back(degrees(d));
  // Twice over: out of range at both ends, then back in.
  std::vector<double> there_and_back = inputs;
  there_and_back.insert(there_and_back.end(), inputs.rbegin(), inputs.rend());
  const kinema::MotionTable table = kinema::solve_motion(model, there_and_back);
  std::size_t ok = 0, unassembled = 0;
  for (std::size_t row = 0; row < there_and_back.size(); ++row) {
    CAPTURE(there_and_back[row] * 180 / M_PI);
    const bool outside = std::fabs(there_and_back[row]) > degrees(71);
    if (outside) CHECK(table.status(row) == kinema::Status::unassembled);
    if (table.status(row) != kinema::Status::ok) {
      unassembled += table.status(row) == kinema::Status::unassembled;
      continue;
    }
    CHECK_FALSE(outside);
    ++ok;
    CHECK(side_of_c(table, row) == 1);  // C above BD, as drawn
  }
  CHECK(ok > 500);
  CHECK(unassembled > 70);
}

TEST_CASE("engine/numeric/dyad_positions: Problem 4.1's parallelogram stays a parallelogram through its change points") {
  const kinema::Model parallelogram = kinema::load_model(kinema_test::sample("problem_4_1_parallelogram.toml"));
  const kinema::Model crossed = kinema::load_model(kinema_test::sample("problem_4_1_antiparallelogram.toml"));
  const double omega1 = 4 * M_PI;  // 120 rpm
  const kinema::MotionTable at30 = kinema::solve_motion(parallelogram, {degrees(30)});
  REQUIRE(at30.status(0) == kinema::Status::ok);
  CHECK(std::fabs(at30.qd(0)[0]) < 1e-9);               // the coupler does not turn
  CHECK(at30.qd(0)[1] == doctest::Approx(omega1));      // the rocker turns with the crank
  CHECK(std::fabs(at30.qdd(0)[1]) < 1e-9);
  std::vector<std::vector<double>> runs;
  for (double step : {1.0, 7.0, 30.0, 45.0}) {
    std::vector<double> inputs;
    for (double d = 0; d <= 720 + 1e-9; d += step) inputs.push_back(degrees(d));
    runs.push_back(inputs);
  }
  runs.push_back({degrees(30), degrees(200), degrees(100), degrees(300), degrees(-30), degrees(185)});
  for (const auto& inputs : runs) {
    CAPTURE(inputs.size());
    for (const kinema::Model* model : {&parallelogram, &crossed}) {
      const bool is_parallelogram = model == &parallelogram;
      CAPTURE(is_parallelogram);
      const kinema::MotionTable table = kinema::solve_motion(*model, inputs);
      std::size_t ok = 0;
      for (std::size_t row = 0; row < inputs.size(); ++row) {
        CAPTURE(inputs[row] * 180 / M_PI);
        const double off_line = std::fabs(std::remainder(inputs[row], M_PI));
        if (off_line < 1e-9) {  // the change points: all joints on one line
          CHECK(table.status(row) == kinema::Status::singular);
          continue;
        }
        REQUIRE(table.status(row) == kinema::Status::ok);
        ++ok;
        // The coupler BC is parallel to AD (theta2 = 0) on the parallelogram, never on the crossed one.
        const double coupler = std::fabs(std::sin(table.q(row)[0]));
        if (is_parallelogram) {
          CHECK(coupler < 1e-9);
          CHECK(std::fabs(table.qd(row)[0]) < 1e-9);
          CHECK(table.qd(row)[1] == doctest::Approx(omega1));
        } else {
          CHECK(coupler > 1e-3);
        }
      }
      CHECK(ok > 0);
    }
  }
}
