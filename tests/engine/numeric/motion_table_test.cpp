// engine/numeric/motion_table: rows stored and read back (set / operator[]),
// what each status keeps, 3-D points, the column storage the block solvers
// write into, set_ok, and one failure per row.
#include <doctest/doctest.h>

#include <vector>

#include "engine/numeric/motion_table.hpp"

using kinema::Failure;
using kinema::MotionState;
using kinema::MotionTable;
using kinema::PointMotion;
using kinema::Status;

namespace {

// A solved state with distinct numbers everywhere (row r, two unknowns, a 2-D and a 3-D point).
MotionState ok_state(double input, double base) {
  MotionState s;
  s.input = input;
  s.input_rate = 5.0;
  s.input_second_rate = -1.0;
  s.status = Status::ok;
  s.q = Eigen::Vector2d(base + 0.1, base + 0.2);
  s.qd = Eigen::Vector2d(base + 1.1, base + 1.2);
  s.qdd = Eigen::Vector2d(base + 2.1, base + 2.2);
  s.loop_residual = 1e-17 * base;
  s.reciprocal_condition = 0.25 + base;
  PointMotion planar;
  planar.dimension = 2;
  planar.position = {base + 10, base + 11, 0};
  planar.velocity = {base + 12, base + 13, 0};
  planar.acceleration = {base + 14, base + 15, 0};
  PointMotion spatial;
  spatial.dimension = 3;
  spatial.position = {base + 20, base + 21, base + 22};
  spatial.velocity = {base + 23, base + 24, base + 25};
  spatial.acceleration = {base + 26, base + 27, base + 28};
  s.points = {planar, spatial};
  return s;
}

void check_same_point(const PointMotion& actual, const PointMotion& expected) {
  REQUIRE(actual.dimension == expected.dimension);
  for (std::size_t c = 0; c < expected.dimension; ++c) {
    CAPTURE(c);
    CHECK(actual.position[c] == expected.position[c]);
    CHECK(actual.velocity[c] == expected.velocity[c]);
    CHECK(actual.acceleration[c] == expected.acceleration[c]);
  }
}

}  // namespace

TEST_CASE("engine/numeric/motion_table: a fresh table is all unassembled, with the given shape") {
  const MotionTable table({0.1, 0.2, 0.3}, 2, {2, 3}, 5.0, -1.0);
  CHECK(table.size() == 3);
  CHECK_FALSE(table.empty());
  CHECK(table.unknown_count() == 2);
  CHECK(table.point_count() == 2);
  CHECK(table.input_rate() == 5.0);
  CHECK(table.input_second_rate() == -1.0);
  CHECK(table.batch_rows() == 0);
  for (std::size_t r = 0; r < 3; ++r) {
    CHECK(table.input(r) == doctest::Approx(0.1 * (r + 1)));
    CHECK(table.status(r) == Status::unassembled);
    CHECK(table.failure(r).kind == Failure::Kind::none);
    const MotionState s = table[r];
    CHECK(s.q.size() == 0);  // no position where none was solved
    CHECK(s.points.empty());
  }
  CHECK(MotionTable().empty());
  // Memory: at least the numbers the shape needs (3 rows x (input, 6 coordinates, 15 point values, 2 diagnostics)).
  CHECK(table.bytes() >= sizeof(double) * 3 * (1 + 6 + 15 + 2));
  CHECK(MotionTable({0.1}, 2, {2, 3}, 0, 0).bytes() < table.bytes());
}

TEST_CASE("engine/numeric/motion_table: set and operator[] round trip, other rows untouched") {
  MotionTable table({0.1, 0.2, 0.3}, 2, {2, 3}, 5.0, -1.0);
  const MotionState written = ok_state(0.2, 1.0);
  table.set(1, written);
  const MotionState read = table[1];
  CHECK(read.input == 0.2);
  CHECK(read.input_rate == 5.0);
  CHECK(read.input_second_rate == -1.0);
  CHECK(read.status == Status::ok);
  CHECK(read.failure.kind == Failure::Kind::none);
  CHECK(read.q == written.q);
  CHECK(read.qd == written.qd);
  CHECK(read.qdd == written.qdd);
  CHECK(read.loop_residual == written.loop_residual);
  CHECK(read.reciprocal_condition == written.reciprocal_condition);
  REQUIRE(read.points.size() == 2);
  check_same_point(read.points[0], written.points[0]);
  check_same_point(read.points[1], written.points[1]);  // 3-D: z kept
  CHECK(read.points[1].position[2] == 23.0);
  CHECK(read.points[1].speed() == doctest::Approx(std::sqrt(24.0 * 24 + 25.0 * 25 + 26.0 * 26)));
  // The accessors agree with the state.
  CHECK(table.q(1)[1] == 1.2);
  CHECK(table.qd(1)[0] == 2.1);
  CHECK(table.qdd(1)[1] == 3.2);
  check_same_point(table.point(1, 1), written.points[1]);
  // Neighbouring rows are not written.
  CHECK(table.status(0) == Status::unassembled);
  CHECK(table.status(2) == Status::unassembled);
  CHECK(table.q(0)[0] == 0.0);
  CHECK(table.q(2)[1] == 0.0);
  CHECK(table.point(2, 1).position[2] == 0.0);

  // Every row set differently, read back by iteration.
  for (std::size_t r = 0; r < 3; ++r) table.set(r, ok_state(0.1 * (r + 1), 100.0 * r));
  std::size_t row = 0;
  for (const MotionState& s : table) {
    CAPTURE(row);
    CHECK(s.q[0] == 100.0 * row + 0.1);
    CHECK(s.points[1].acceleration[2] == 100.0 * row + 28);
    ++row;
  }
  CHECK(row == 3);
}

TEST_CASE("engine/numeric/motion_table: column storage: value i of row r at [i * size() + r]") {
  MotionTable table({0.0, 1.0, 2.0, 3.0}, 2, {3}, 1.0, 0.0);
  table.set(2, ok_state(2.0, 7.0));
  CHECK(table.q_values()[0 * 4 + 2] == 7.1);
  CHECK(table.q_values()[1 * 4 + 2] == 7.2);
  CHECK(table.qd_values()[1 * 4 + 2] == 8.2);
  CHECK(table.qdd_values()[0 * 4 + 2] == 9.1);
  CHECK(table.loop_residuals()[2] == 1e-17 * 7.0);
  CHECK(table.reciprocal_conditions()[2] == 7.25);
  // set() takes points only when the state has as many as the table: this state has two, the table one.
  CHECK(table.point_values()[0 * 4 + 2] == 0.0);
  MotionState one_point = ok_state(2.0, 7.0);
  one_point.points.erase(one_point.points.begin());
  table.set(2, one_point);
  // The table's one point is 3-D: x, y, z, vx, vy, vz, ax, ay, az, each a column.
  for (std::size_t c = 0; c < 9; ++c) {
    CAPTURE(c);
    CHECK(table.point_values()[c * 4 + 2] == 27.0 + c);
  }
  // Writing the columns directly is what the block solver does; set_ok then marks the rows.
  table.q_values()[0 * 4 + 3] = -0.5;
  table.point_values()[2 * 4 + 3] = 42.0;  // z of the point at row 3
  table.set_ok(3, 1);
  CHECK(table.status(3) == Status::ok);
  CHECK(table[3].q[0] == -0.5);
  CHECK(table[3].points.at(0).position[2] == 42.0);
}

TEST_CASE("engine/numeric/motion_table: what each status keeps, one failure per row") {
  MotionTable table({0.1, 0.2, 0.3, 0.4}, 2, {2, 3}, 5.0, -1.0);
  MotionState singular = ok_state(0.1, 1.0);
  singular.status = Status::singular;
  singular.failure.kind = Failure::Kind::singular_jacobian;
  table.set(0, singular);

  MotionState open;
  open.input = 0.2;
  open.status = Status::unassembled;
  open.failure.kind = Failure::Kind::group_open;
  open.failure.group = 1;
  open.failure.residual = 0.003;
  open.failure.from_guesses = false;
  table.set(1, open);

  MotionState stops;
  stops.input = 0.3;
  stops.status = Status::unassembled;
  stops.failure.kind = Failure::Kind::branch_stops;
  stops.failure.from = 0.2;
  stops.failure.stopped_at = 0.25;
  table.set(2, stops);

  MotionState resumed = ok_state(0.4, 2.0);
  resumed.failure.kind = Failure::Kind::resumed_after_gap;
  table.set(3, resumed);

  // Singular: the position, no rates, no points.
  const MotionState s0 = table[0];
  CHECK(s0.status == Status::singular);
  CHECK(s0.failure.kind == Failure::Kind::singular_jacobian);
  CHECK(s0.q == singular.q);
  CHECK(s0.qd.size() == 0);
  CHECK(s0.qdd.size() == 0);
  CHECK(s0.points.empty());
  // Unassembled: nothing but the failure, each with its own data.
  const MotionState s1 = table[1];
  CHECK(s1.status == Status::unassembled);
  CHECK(s1.q.size() == 0);
  CHECK(s1.failure.kind == Failure::Kind::group_open);
  CHECK(s1.failure.group == 1);
  CHECK(s1.failure.residual == 0.003);
  CHECK_FALSE(s1.failure.from_guesses);
  CHECK(table.failure(2).kind == Failure::Kind::branch_stops);
  CHECK(table.failure(2).from == 0.2);
  CHECK(table.failure(2).stopped_at == 0.25);
  // ok with a note.
  CHECK(table.status(3) == Status::ok);
  CHECK(table.failure(3).kind == Failure::Kind::resumed_after_gap);
  CHECK(table[3].qd == resumed.qd);

  // A row copied from another table is what storing its MotionState stores: every column
  // (stale values where the status says nothing, too) and the failure, for each status.
  MotionTable state_copied({9, 9, 9, 9, 9}, 2, {2, 3}, 5.0, -1.0), row_copied = state_copied;
  for (std::size_t r = 0; r < 4; ++r) {
    state_copied.set(4 - r, table[r]);
    row_copied.set(4 - r, table, r);
  }
  for (std::size_t r = 0; r < 5; ++r) {
    CAPTURE(r);
    CHECK(row_copied.input(r) == state_copied.input(r));
    CHECK(row_copied.status(r) == state_copied.status(r));
    CHECK(row_copied.failure(r).kind == state_copied.failure(r).kind);
    CHECK(row_copied.failure(r).residual == state_copied.failure(r).residual);
    CHECK(row_copied.loop_residual(r) == state_copied.loop_residual(r));
    CHECK(row_copied.reciprocal_condition(r) == state_copied.reciprocal_condition(r));
    for (std::size_t i = 0; i < 2; ++i) {
      CHECK(row_copied.q_column(i)[r] == state_copied.q_column(i)[r]);
      CHECK(row_copied.qd_column(i)[r] == state_copied.qd_column(i)[r]);
      CHECK(row_copied.qdd_column(i)[r] == state_copied.qdd_column(i)[r]);
    }
    for (std::size_t k = 0; k < 15; ++k) CHECK(row_copied.point_column(k < 6 ? 0 : 1, k < 6 ? k : k - 6)[r] == state_copied.point_column(k < 6 ? 0 : 1, k < 6 ? k : k - 6)[r]);
  }
  CHECK(row_copied.q_column(1)[4] == singular.q[1]);  // the copies went where they should
  CHECK(row_copied.point_column(1, 8)[1] == resumed.points[1].acceleration[2]);
  // Frames (spatial chains) come with the points' columns.
  MotionTable framed({0.1}, 1, {}, 1.0, 0.0, 1), framed_copy({0.5, 0.6}, 1, {}, 1.0, 0.0, 1);
  MotionState turning;
  turning.status = Status::ok;
  turning.q = turning.qd = turning.qdd = Eigen::VectorXd::Constant(1, 0.5);
  turning.frames = {kinema::FrameMotion{{1, 2, 3}, {4, 5, 6}}};
  framed.set(0, turning);
  framed_copy.set(1, framed, 0);
  CHECK(framed_copy.frame(1, 0).angular_acceleration[2] == 6.0);
  CHECK(framed_copy.qd(1)[0] == 0.5);
  CHECK(framed_copy.status(0) == Status::unassembled);

  // set_ok marks rows ok and clears their failures, and only those rows.
  table.set_ok(1, 2);
  CHECK(table.status(0) == Status::singular);
  CHECK(table.status(1) == Status::ok);
  CHECK(table.status(2) == Status::ok);
  CHECK(table.failure(1).kind == Failure::Kind::none);
  CHECK(table.failure(2).kind == Failure::Kind::none);
  CHECK(table.failure(3).kind == Failure::Kind::resumed_after_gap);
  CHECK(table.failure(0).kind == Failure::Kind::singular_jacobian);

  CHECK(std::string(kinema::status_name(Status::ok)) == "ok");
  CHECK(std::string(kinema::status_name(Status::singular)) == "singular");
  CHECK(std::string(kinema::status_name(Status::unassembled)) == "unassembled");

  table.add_batch_rows(32);
  table.add_batch_rows(32);
  CHECK(table.batch_rows() == 64);
}
