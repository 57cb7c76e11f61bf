// Sweeps keep the assembly branch, agree with hand-written closed forms, and
// mark positions that cannot be assembled or are singular instead of
// printing numbers there.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "engine/model.hpp"
#include "linkages/vector_loop_file.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

namespace {
constexpr double deg = M_PI / 180.0;

// A non-Grashof four-bar (triple rocker): the crank cannot turn all the way round.
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

// Hand-written closed form of the sample four-bar (a, b, c, d = 40, 120, 80, 100 mm),
// open branch: B is where the circles about A (radius b) and D (radius c) meet,
// on the left of the diagonal from A to D.
struct FourBarPosition {
  double theta3, theta4;
};
FourBarPosition four_bar_open(double theta2) {
  const double a = 0.04, b = 0.12, c = 0.08, d = 0.1;
  const double ax = a * std::cos(theta2), ay = a * std::sin(theta2);
  const double diagonal = std::hypot(d - ax, -ay);
  const double diagonal_angle = std::atan2(-ay, d - ax);
  const double at_a = std::acos((b * b + diagonal * diagonal - c * c) / (2 * b * diagonal));
  const double theta3 = diagonal_angle + at_a;
  const double bx = ax + b * std::cos(theta3), by = ay + b * std::sin(theta3);
  return {theta3, std::atan2(by, bx - d)};
}
}

TEST_CASE("four-bar sweep keeps the open branch and matches the closed form") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  std::vector<double> inputs;
  for (int i = 0; i <= 360; ++i) inputs.push_back(i * deg);
  const double w2 = model.system.input.rate_value;
  const auto states = kinema::solve_motion(model, inputs, kinema_test::with_rates(w2, 0.0));
  const double a = 0.04, b = 0.12, c = 0.08;
  for (const auto& s : states) {
    REQUIRE(s.status == kinema::Status::ok);
    const double t2 = s.input;
    const auto [t3, t4] = four_bar_open(t2);
    CAPTURE(s.input / deg);
    CHECK(std::remainder(s.q[1] - t4, 2 * M_PI) == doctest::Approx(0).epsilon(1e-9));
    CHECK(std::remainder(s.q[0] - t3, 2 * M_PI) == doctest::Approx(0).epsilon(1e-9));
    CHECK(s.qd[0] == doctest::Approx(a * w2 * std::sin(t4 - t2) / (b * std::sin(t3 - t4))).epsilon(1e-9));
    CHECK(s.qd[1] == doctest::Approx(a * w2 * std::sin(t2 - t3) / (c * std::sin(t4 - t3))).epsilon(1e-9));
  }
}

TEST_CASE("a non-Grashof four-bar: the sweep stops at the limit and says so") {
  const std::string path = kinema_test::write_temporary("triple_rocker.toml", kTripleRocker);
  const auto result = kinema_test::run_kinema({"eval", path, "--sweep", "0:360:10", "--format", "json"});
  REQUIRE(result.exit_status == 0);
  CHECK(result.err.find("warning") != std::string::npos);
  const auto doc = nlohmann::json::parse(result.out);
  int ok = 0, unassembled = 0;
  for (const auto& row : doc["results"]) {
    if (row["status"] == "ok") {
      ++ok;
      CHECK(row["coordinates"]["theta3"]["rate"].is_number());
    } else if (row["status"] == "singular") {
      // The toggles at 0, 120 and 240 deg (|AD| = c - b or b + c) lie on the grid.
      CHECK(row["coordinates"]["theta3"]["value"].is_number());
      CHECK(row["coordinates"]["theta3"]["rate"].is_null());  // never NaN or huge numbers
      CHECK(row["points"].empty());
    } else {
      ++unassembled;
      CHECK(row["status"] == "unassembled");
      CHECK(row["message"].get<std::string>().find("theta2 = ") != std::string::npos);
      CHECK(row["coordinates"].empty());  // no numbers where there is no position
    }
  }
  CHECK(ok > 0);
  CHECK(unassembled > 0);
  // A single value out of range is an error with the loop and the angle.
  const auto single = kinema_test::run_kinema({"eval", path, "--angle", "180"});
  CHECK(single.exit_status == 3);
  CHECK(single.out.empty());
  CHECK(single.err.find("loop \"ABCD\"") != std::string::npos);
  CHECK(single.err.find("theta2 = 180 deg") != std::string::npos);
}

TEST_CASE("list of angles far apart is continued on the same branch") {
  // From the open-branch guess at 40 deg, jump straight to 220 deg: continuation
  // must land on the open branch there too (theta4 as the closed form gives it).
  const auto doc = kinema_test::eval_json("four_bar.toml", {"--angle", "40", "--angle", "220"});
  REQUIRE(doc["results"].size() == 2);
  const double t4 = four_bar_open(220 * deg).theta4 / deg;
  CHECK(std::remainder(doc["results"][1]["coordinates"]["theta4"]["value"].get<double>() - t4, 360.0) ==
        doctest::Approx(0).epsilon(1e-7));
}

TEST_CASE("dead centre of the piston-driven crank is reported as singular, never as numbers") {
  const auto single = kinema_test::run_kinema({"eval", kinema_test::sample("piston_driven_crank.toml"), "--at", "200"});
  CHECK(single.exit_status == 4);
  CHECK(single.out.empty());
  CHECK(single.err.find("singular position at x = 200 mm") != std::string::npos);
  CHECK(single.err.find("toggle or dead-centre") != std::string::npos);

  const auto sweep = kinema_test::run_kinema(
      {"eval", kinema_test::sample("piston_driven_crank.toml"), "--sweep", "150:200:10", "--format", "csv"});
  REQUIRE(sweep.exit_status == 0);
  CHECK(sweep.out.find("nan") == std::string::npos);
  CHECK(sweep.out.find("inf") == std::string::npos);
  const auto last_line_start = sweep.out.rfind('\n', sweep.out.size() - 2) + 1;
  const std::string last = sweep.out.substr(last_line_start);
  CHECK(last.find(",singular,") != std::string::npos);
  // The rate columns of that row are empty.
  CHECK(last.find(",,") != std::string::npos);
}

TEST_CASE("Workspace::advance steps along the open branch and refuses to cross a limit") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const double w2 = model.system.input.rate_value, a2 = 3.0;
  kinema::Workspace workspace(model);
  kinema::MotionState state = kinema::solve_motion(model, {0.0}, kinema_test::with_rates(w2, a2))[0];
  REQUIRE(state.status == kinema::Status::ok);
  // Small steps (the predicted path) and a 30 deg jump (continuation) over two turns.
  for (double theta = 0.1 * deg; theta <= 720 * deg; theta += (theta > 400 * deg ? 30 : 0.1) * deg) {
    REQUIRE(workspace.advance(theta, w2, a2, state));
    CAPTURE(theta / deg);
    const auto [t3, t4] = four_bar_open(theta);
    CHECK(state.status == kinema::Status::ok);
    CHECK(state.input == theta);
    CHECK(std::remainder(state.q[0] - t3, 2 * M_PI) == doctest::Approx(0).epsilon(1e-12));
    CHECK(std::remainder(state.q[1] - t4, 2 * M_PI) == doctest::Approx(0).epsilon(1e-12));
    CHECK(state.qd[0] == doctest::Approx(0.04 * w2 * std::sin(t4 - theta) / (0.12 * std::sin(t3 - t4))).epsilon(1e-10));
  }

  // The triple rocker cannot turn through 180 deg: advance says so and keeps the state.
  const kinema::Model rocker = kinema::load_model(kinema_test::write_temporary("rocker_advance.toml", kTripleRocker));
  kinema::Workspace rocker_workspace(rocker);
  kinema::MotionState at_90 = kinema::solve_motion(rocker, {90 * deg}, kinema_test::with_rates(1.0, 0.0))[0];
  REQUIRE(at_90.status == kinema::Status::ok);
  const kinema::MotionState before = at_90;
  CHECK_FALSE(rocker_workspace.advance(180 * deg, 1.0, 0.0, at_90));
  CHECK(at_90.input == before.input);
  CHECK(at_90.q == before.q);
}

// Session 30's review: the parallelogram of Problem 4.1 as the vector loops kinema writes
// for it, swept through its change point at 180 deg, had every row after it unassembled
// ("the links do not reach"): Newton started from the folded, singular position has no
// direction to go. From the last ok row's motion carried on past it, it runs on as the
// joints-and-links file does (the parallelogram kept).
TEST_CASE("branch: a vector-loop sweep runs on past a singular row (the parallelogram through its change point)") {
  const kinema::Mechanism drawn = kinema::read_mechanism_file(kinema_test::sample("problem_4_1_parallelogram.toml"));
  const kinema::Model joints = kinema::make_model(drawn);
  const kinema::Model loops = kinema::make_model(kinema::read_mechanism_text(kinema_test::loops_file(drawn), "loops.toml"));
  REQUIRE(loops.kinematics.closed_form() == nullptr);
  std::vector<double> inputs;
  for (int d = 0; d <= 350; d += 10) inputs.push_back(d * deg);
  const kinema::MotionTable by_loops = kinema::solve_motion(loops, inputs), by_joints = kinema::solve_motion(joints, inputs);
  for (std::size_t row = 0; row < inputs.size(); ++row) {
    CAPTURE(inputs[row] / deg);
    REQUIRE(by_loops.status(row) != kinema::Status::unassembled);
    CHECK(by_loops.status(row) == by_joints.status(row));
    // At a change point (singular: 0 and 180 deg) a position is known to the square root of rounding.
    const double tolerance = by_joints.status(row) == kinema::Status::ok ? 1e-9 : 1e-6;
    for (Eigen::Index i = 0; i < by_loops.q(row).size(); ++i)
      CHECK(std::fabs(std::remainder(by_loops.q(row)[i] - by_joints.q(row)[i], 2 * M_PI)) < tolerance);
  }
}
