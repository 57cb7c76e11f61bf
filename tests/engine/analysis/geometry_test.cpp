// engine/analysis/geometry: the loops' terms as segments at a solved position.
// Each loop's chain of link vectors ends where it starts; the joints are where
// the closed form puts them; ground, links and sliders are told apart.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>

#include "engine/analysis/geometry.hpp"
#include "engine/analysis/motion_drawing.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/constraints/output_columns.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::DrawingSegment;
using kinema::MotionState;
using kinema_unit::kDeg;

namespace {

bool near(std::complex<double> a, std::complex<double> b, double tolerance = 1e-12) {
  return std::abs(a - b) <= tolerance;
}

}  // namespace

TEST_CASE("engine/analysis/geometry: four-bar segments at a closed-form position") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::MechanismGeometry geometry(model);
  const kinema_unit::FourBar four_bar;
  for (double degrees : {40.0, 150.0, 290.0}) {
    CAPTURE(degrees);
    const double t2 = degrees * kDeg, t3 = four_bar.theta3(t2), t4 = four_bar.theta4(t2);
    MotionState state;
    state.input = t2;
    state.status = kinema::Status::ok;
    state.q = Eigen::Vector2d(t3, t4);
    const auto segments = geometry.segments(state);
    REQUIRE(segments.size() == 4);  // a, b, -c, -d as written
    const std::complex<double> A = std::polar(0.04, t2), B = A + std::polar(0.12, t3), D(0.1, 0);
    CHECK(near(segments[0].from, 0));
    CHECK(near(segments[0].to, A));
    CHECK(near(segments[1].to, B));
    CHECK(near(segments[2].to, D));  // B - c e^{i t4} is the rocker's pivot
    CHECK(near(B, D + std::polar(0.08, t4)));
    // A chain: each segment starts where the one before ends, and the last ends at the start.
    for (std::size_t k = 1; k < segments.size(); ++k) CHECK(segments[k].from == segments[k - 1].to);
    CHECK(near(segments.back().to, segments.front().from, 1e-15));
    CHECK(segments[0].kind == DrawingSegment::Kind::link);
    CHECK(segments[1].kind == DrawingSegment::Kind::link);
    CHECK(segments[2].kind == DrawingSegment::Kind::link);
    CHECK(segments[3].kind == DrawingSegment::Kind::ground);
    // Every joint is a pin; the ground's ends are the two fixed pivots.
    for (const DrawingSegment& g : segments) CHECK((g.pin_at_from && g.pin_at_to));
  }
  // No position, no drawing.
  MotionState unassembled;
  unassembled.input = 0.3;
  CHECK(geometry.segments(unassembled).empty());
}

TEST_CASE("engine/analysis/geometry: a slider's guide, and two loops each closing on its own") {
  const kinema::Model slider = kinema::load_model(kinema_test::sample("slider_crank.toml"));
  kinema::Workspace workspace(slider);
  Eigen::VectorXd q = slider.kinematics.guess();
  REQUIRE(workspace.solve_position(60 * kDeg, q));
  MotionState state = workspace.motion(60 * kDeg, 1.0, 0.0, q);
  const auto segments = kinema::MechanismGeometry(slider).segments(state);
  REQUIRE(segments.size() == 3);  // a e^{i t2}, b e^{i t3}, -(x + i e)
  CHECK(segments[0].kind == DrawingSegment::Kind::link);
  CHECK(segments[1].kind == DrawingSegment::Kind::link);
  CHECK(segments[2].kind == DrawingSegment::Kind::slider);
  // The rod ends at the piston pin (x, e).
  CHECK(near(segments[1].to, std::complex<double>(q[1], 0.01)));
  CHECK(near(segments[2].to, 0, 1e-15));

  // Problem 4.4: ABCD (4 terms) then DEF (5 terms), each starting at the origin and closing.
  const kinema::Model six = kinema::load_model(kinema_test::sample("problem_4_4_six_bar.toml"));
  const auto table = kinema::solve_motion(six, {30 * kDeg});
  REQUIRE(table.status(0) == kinema::Status::ok);
  const auto drawn = kinema::MechanismGeometry(six).segments(table[0]);
  REQUIRE(drawn.size() == 4 + 5);
  CHECK(near(drawn[0].from, 0));
  CHECK(near(drawn[3].to, 0, 1e-14));
  CHECK(near(drawn[4].from, 0));
  CHECK(near(drawn[8].to, 0, 1e-14));
  // The joints the points name: B = AB e^{i phi} ends the first segment; C ends the second.
  const auto& points = table[0].points;
  CHECK(near(drawn[0].to, {points[0].position[0], points[0].position[1]}));
  CHECK(near(drawn[1].to, {points[1].position[0], points[1].position[1]}));
  // In DEF, E ends the third term and F is where the slider's vector starts.
  CHECK(near(drawn[6].to, {points[2].position[0], points[2].position[1]}));
  CHECK(near(drawn[7].to, {points[3].position[0], points[3].position[1]}));
  CHECK(drawn[4].kind == DrawingSegment::Kind::ground);
  CHECK(drawn[5].kind == DrawingSegment::Kind::ground);
  CHECK(drawn[8].kind == DrawingSegment::Kind::slider);

  // Problem 3.22: the second loop's -d - i r6 meet at (d, 0), the foot of D's fixed guide,
  // which is no joint (drawn as a pivot there before); A, C, D, B and O2 are.
  const kinema::Model p322 = kinema::load_model(kinema_test::sample("problem_3_22_six_bar_sliders.toml"));
  const auto solved = kinema::solve_motion(p322, {-120 * kDeg});
  REQUIRE(solved.status(0) == kinema::Status::ok);
  const auto terms = kinema::MechanismGeometry(p322).segments(solved[0]);
  double d = 0;
  for (const auto& p : p322.system.parameters)
    if (p.symbol.get_name() == "d") d = p.value;
  std::size_t ends_at_foot = 0;
  for (const DrawingSegment& g : terms) {
    for (const auto& [end, pinned] : {std::pair(g.from, g.pin_at_from), std::pair(g.to, g.pin_at_to)}) {
      const bool foot = near(end, d, 1e-12);
      ends_at_foot += foot;
      CHECK(pinned == !foot);
    }
  }
  CHECK(ends_at_foot == 2);
}

TEST_CASE("engine/analysis/geometry: each link's angular velocity off the model's tape") {
  // Every vector-loop sample: a link turning with a coordinate's rate turns at the value
  // the state solved for that rate (instant centres read these, not GiNaC).
  int checked = 0;
  for (const char* name : kinema_test::kSamples) {
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::ConstraintSystem& system = model.system;
    if (system.plan || !system.frames.empty()) continue;
    CAPTURE(std::string(name));
    const kinema::MechanismGeometry geometry(model);
    std::vector<double> inputs = system.input.values;
    if (inputs.empty()) inputs = {0.3};
    for (const MotionState& s : kinema::solve_motion(model, inputs)) {
      if (s.status != kinema::Status::ok) continue;
      const auto omegas = geometry.link_angular_velocities(s);
      REQUIRE(omegas.size() == geometry.link_rates().size());
      for (std::size_t k = 0; k < omegas.size(); ++k) {
        const GiNaC::ex& rate = geometry.link_rates()[k];
        std::optional<double> solved;
        if (rate.is_equal(system.input.rate)) solved = s.input_rate;
        for (std::size_t j = 0; j < system.unknowns.size(); ++j)
          if (rate.is_equal(system.unknowns[j].rate)) solved = s.qd[Eigen::Index(j)];
        if (!solved) continue;
        REQUIRE(omegas[k]);
        CHECK(*omegas[k] == *solved);
        ++checked;
      }
    }
  }
  CHECK(checked >= 12);
  // No position, no angular velocities.
  const kinema::Model four_bar = kinema::load_model(kinema_test::sample("four_bar.toml"));
  MotionState unassembled;
  unassembled.input = 0.3;
  for (const auto& omega : kinema::MechanismGeometry(four_bar).link_angular_velocities(unassembled)) CHECK(!omega);
}

// The page re-solves joints files with the tape alone: its drawing stage must give what
// the file's rows draw in closed form (joints, blocks, fixed guides) and the extra
// result columns as eval writes them, at every row of a turn.
TEST_CASE("engine/analysis/geometry: a joints file's drawing stage places its joints and gives its extra columns") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_4_1_parallelogram.toml"}) {
    const std::string sample = name;
    CAPTURE(sample);
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::ConstraintSystem& system = model.system;
    const kinema::TapeLayout& layout = model.kinematics.layout();
    REQUIRE(layout.linkage_joint_count == system.plan->joints.size());
    const kinema::OutputScale scale(system);
    REQUIRE(scale.length == 1.0);  // the columns below compared in SI
    std::vector<double> inputs;
    for (int k = 0; k < 36; ++k) inputs.push_back(k * 10 * M_PI / 180);
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    const kinema::MotionDrawing drawing = kinema::motion_drawing(model, table);
    REQUIRE(drawing.rows.size() == table.size());
    const std::size_t width = kinema::result_column_count(system), begin = kinema::linkage_columns_begin(system);
    REQUIRE(layout.linkage_column_count == width - begin);
    std::size_t checked = 0;
    for (std::size_t r = 0; r < table.size(); ++r) {
      if (table.status(r) != kinema::Status::ok) continue;
      const kinema::MotionState state = table[r];
      const std::vector<double> drawn = model.kinematics.drawing_values(state);
      const auto placed = kinema::linkage_drawing(system, state);
      REQUIRE(placed);
      CAPTURE(r);
      const auto close = [&](double tape, double expected) {
        CHECK(std::abs(tape - expected) <= 1e-9 * (1 + std::abs(expected)));
      };
      const auto joint_at = [&](const std::string& joint) {
        for (std::size_t j = 0; j < system.plan->joints.size(); ++j)
          if (system.plan->joints[j].name == joint) return layout.linkage_joint_output(j);
        FAIL("no joint " << joint);
        return std::size_t(0);
      };
      // Each joint where the page's file rows put it (motion_drawing: one place a name, a
      // slider's joint at its block's pin), each block at its angle.
      const std::vector<double>& row = drawing.rows[r];
      REQUIRE(row.size() == 2 * drawing.joint_names.size() + layout.linkage_block_count);
      for (std::size_t j = 0; j < drawing.joint_names.size(); ++j) {
        CAPTURE(drawing.joint_names[j]);
        close(drawn[joint_at(drawing.joint_names[j])], row[2 * j]);
        close(drawn[joint_at(drawing.joint_names[j]) + 1], row[2 * j + 1]);
        ++checked;
      }
      for (std::size_t b = 0; b < layout.linkage_block_count; ++b)
        close(std::remainder(drawn[layout.linkage_block_output(b)] - row[2 * drawing.joint_names.size() + b], 2 * M_PI), 0);
      for (std::size_t g = 0; g < placed->guides.size(); ++g) {
        // The guide's point where the coordinate is 0 lies on the closed form's line.
        const std::size_t k = layout.linkage_guide_output(g);
        const std::complex<double> through(drawn[k], drawn[k + 1]), along(drawn[k + 2], drawn[k + 3]);
        close(std::abs(along - placed->guides[g].along), 0);
        close(std::imag((through - placed->guides[g].through) * std::conj(along)), 0);
      }
      std::vector<double> values(width);
      kinema::result_values(system, scale, table, r, values.data());
      const std::vector<kinema::ResultColumn> columns = kinema::result_columns(system, scale);
      for (std::size_t c = begin; c < width; ++c) {
        CAPTURE(columns[c].name);
        double tape = drawn[layout.linkage_column_output(c - begin)];
        if (columns[c].unit == "deg") tape = scale.coordinate(kinema::Dimension::angle, tape);
        close(tape, values[c]);
        ++checked;
      }
    }
    CHECK(checked > 0);
  }
}

// What the drawing's arrows and angle marks are placed by: two arrows from one point are as
// near as a tip comes to the other arrow (their common start left out); from two starts,
// also a start to the other arrow, and 0 where they cross. An angle mark's radius is its
// symbol's where that is within the bounds, and never past its link.
TEST_CASE("engine/analysis/geometry: distances between arrows, an angle mark's radius") {
  using P = std::complex<double>;
  CHECK(kinema::arrows_distance(0, P(2, 0), 0, P(1, 0)) == 0);                            // one along the other
  CHECK(kinema::arrows_distance(0, P(2, 0), 0, P(-1, 0)) == doctest::Approx(1));         // opposite: 1 tip to start
  CHECK(kinema::arrows_distance(0, P(2, 0), 0, P(0, 1)) == doctest::Approx(1));          // square: the short tip
  CHECK(kinema::arrows_distance(0, P(2, 0), P(0, 0.3), P(1, 0)) == doctest::Approx(0.3)); // side by side
  CHECK(kinema::arrows_distance(0, P(2, 0), P(1, -1), P(0, 2)) == 0);                     // crossing
  const double pi = 3.14159265358979323846;
  CHECK(kinema::angle_mark_radius(pi / 2, 0.4, 10, 0.55, 0.9, 0.8) == doctest::Approx(0.4 / std::sin(pi / 4)));
  CHECK(kinema::angle_mark_radius(pi, 0.4, 10, 0.55, 0.9, 0.8) == doctest::Approx(0.55));
  CHECK(kinema::angle_mark_radius(pi / 60, 0.4, 10, 0.55, 0.9, 0.8) == doctest::Approx(0.9));  // 3 degrees: no wider
  CHECK(kinema::angle_mark_radius(-pi / 60, 0.4, 10, 0.55, 0.9, 0.8) == doctest::Approx(0.9));
  CHECK(kinema::angle_mark_radius(pi / 60, 0.4, 0.5, 0.55, 0.9, 0.8) == doctest::Approx(0.4));  // a short link
  CHECK(kinema::angle_mark_radius(pi / 60, 0.4, 0, 0.55, 0.9, 0.8) == doctest::Approx(0.9));    // no link known
}
