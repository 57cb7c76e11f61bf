// Following a joints-and-links mechanism as it really moves, through its toggles: at a
// toggle (a dyad's links in line, the input at the end of its range) the input reverses
// and that dyad changes assembly, so a triple rocker's coupler curve comes out as one
// closed motion. The rows are the input grid start + k * step, walked forth and back,
// with a row at each toggle.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/numeric/kinematics.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

/// Rows a circuit may have (it is held in memory, like a list of values): a million rows
/// draw any coupler curve finer than a plotter can.
constexpr std::size_t kMaxCircuitRows = 1'000'000;
/// Rows times unknowns a circuit may have: each row is a position with its rates (a dense
/// solve of all unknowns), so a long chain has fewer rows. --circuit 0.002 on a chain of 63
/// links (180,000 rows a turn) worked 15-47 s; a circuit that cannot fit is refused at once.
constexpr std::size_t kMaxCircuitRowUnknowns = 1'000'000;

struct CircuitSettings {
  double start = 0;        ///< Input value the circuit starts and ends at (SI), on the sketch's assembly.
  double step = 0;         ///< Input step between rows (SI, > 0).
  double rate = 0;         ///< Input rate (SI) at the start; it changes sign at each toggle.
  double second_rate = 0;  ///< Input second rate (SI); changes sign with the rate.
  std::size_t max_rows = 0;  ///< More rows than this: stop (Circuit::Stop::too_many_rows).
};

struct Circuit {
  enum class Stop {
    closed,         ///< Back at the start, in the same direction, on the same assembly (or a full turn).
    start_open,     ///< Dyad `dyad` cannot close at the start.
    locked,         ///< Two toggles at one value: the mechanism cannot move (dyad `dyad`).
    too_many_rows,  ///< Not closed within max_rows rows.
  };
  Stop stop = Stop::closed;
  std::uint32_t dyad = 0;
  std::size_t toggles = 0;
  /// Rows along the circuit (MotionTable::is_circuit): toggle rows are singular with
  /// Failure::Kind::circuit_toggle; empty unless closed.
  MotionTable table;
};

/// The circuit of a mechanism solved in closed form (kinematics.closed_form() != nullptr);
/// InputError for a step that is not a positive number, or a model not in closed form.
Circuit solve_circuit(const Kinematics& kinematics, const CircuitSettings& settings);

}  // namespace kinema
