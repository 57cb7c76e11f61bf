// engine/numeric/sweep: SweepSolver, the serial run a block at a time, gives the rows of
// solve_sweep bit for bit, whatever the block size (blocks that cut a SIMD block, blocks
// of one row) and through singular and unassembled rows.
#include <doctest/doctest.h>

#include <cstring>

#include "engine/model.hpp"
#include "engine/numeric/sweep.hpp"
#include "tests/test_support.hpp"

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void check_same_row(const kinema::MotionTable& whole, std::size_t row, const kinema::MotionTable& block,
                    std::size_t block_row) {
  CAPTURE(row);
  REQUIRE(whole.status(row) == block.status(block_row));
  REQUIRE(whole.failure(row).kind == block.failure(block_row).kind);
  CHECK(same_bits(whole.input(row), block.input(block_row)));
  CHECK(same_bits(whole.loop_residual(row), block.loop_residual(block_row)));
  CHECK(same_bits(whole.reciprocal_condition(row), block.reciprocal_condition(block_row)));
  // What the status makes valid (MotionState says which).
  if (whole.status(row) == kinema::Status::unassembled) return;
  for (Eigen::Index i = 0; i < Eigen::Index(whole.unknown_count()); ++i) REQUIRE(same_bits(whole.q(row)[i], block.q(block_row)[i]));
  if (whole.status(row) != kinema::Status::ok) return;
  for (Eigen::Index i = 0; i < Eigen::Index(whole.unknown_count()); ++i) {
    REQUIRE(same_bits(whole.qd(row)[i], block.qd(block_row)[i]));
    REQUIRE(same_bits(whole.qdd(row)[i], block.qdd(block_row)[i]));
  }
  for (std::size_t p = 0; p < whole.point_count(); ++p) {
    const kinema::PointMotion a = whole.point(row, p), b = block.point(block_row, p);
    for (std::size_t c = 0; c < a.dimension; ++c) {
      REQUIRE(same_bits(a.position[c], b.position[c]));
      REQUIRE(same_bits(a.velocity[c], b.velocity[c]));
      REQUIRE(same_bits(a.acceleration[c], b.acceleration[c]));
    }
  }
}

}  // namespace

TEST_CASE("engine/numeric/sweep: SweepSolver block by block equals solve_sweep bit for bit on every sample") {
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const auto& input = model.system.input;
    // A sweep in the file's units: angles over a turn and a bit; the slider input from
    // inside its range out past where the mechanism comes apart (singular, unassembled).
    const bool angle = input.dimension == kinema::Dimension::angle;
    const kinema::InputValues values = angle ? kinema::InputValues::sweep(-10, 0.13, 3000, M_PI / 180)
                                             : kinema::InputValues::sweep(60, 0.05, 3000, 1e-3);
    kinema::SweepSettings settings;
    settings.rate = input.rate_value;
    settings.second_rate = input.second_rate_value;
    const kinema::MotionTable whole = kinema::solve_sweep(model.kinematics, values.to_vector(), settings);
    std::size_t failures = 0;
    for (std::size_t row = 0; row < whole.size(); ++row) failures += whole.status(row) != kinema::Status::ok;
    if (input.dimension == kinema::Dimension::length) CHECK(failures > 100);  // the comparison covers failed rows too
    CHECK(whole.batch_rows() > 0);
    for (std::size_t block_rows : {1u, 7u, 31u, 33u, 37u, 500u, 4096u}) {
      CAPTURE(block_rows);
      kinema::SweepSolver solver(model.kinematics, values, settings);
      kinema::SweepBlock block;
      std::size_t next = 0, batch_rows = 0;
      while (!solver.done()) {
        solver.solve_next(block, block_rows);
        REQUIRE(block.run_row == next);
        REQUIRE(block.size() >= std::min(block_rows, whole.size() - next));
        batch_rows += block.table.batch_rows();
        for (std::size_t r = block.first; r < block.last; ++r) check_same_row(whole, next++, block.table, r);
      }
      CHECK(next == whole.size());
      CHECK(batch_rows == whole.batch_rows());
    }
  }
}
