// What went wrong at one input value, as data: the numeric core says what
// happened and where; the analysis stage (engine/analysis/diagnostics) makes the sentence.
#pragma once

#include <cstdint>

namespace kinema {

enum class Status {
  ok,           ///< Position, rates and second rates are valid.
  singular,     ///< Position valid; Phi_q rank-deficient, rates undefined.
  unassembled,  ///< The equations cannot be closed (on this branch) at this input.
};

const char* status_name(Status status);

struct Failure {
  enum class Kind : std::uint8_t {
    none,                  ///< Nothing to report.
    resumed_after_gap,     ///< ok, but after unassembled or singular values: the branch may differ.
    group_open,            ///< Newton could not close `group`; `residual` is what stayed open.
    branch_stops,          ///< Continuation from `from` stopped near `stopped_at` (limit or toggle).
    too_far,               ///< Continuation from `from` refused: too many steps, or too large to step.
    singular_jacobian,     ///< Phi_q rank-deficient (toggle or dead centre).
    nonfinite_rates,       ///< A formula divides by zero at this position.
    point_undefined,       ///< Rates defined, but point `group`'s formula gives no number here (sqrt of a negative).
    dyad_open,             ///< Joints and links: dyad `group` (in solving order) cannot close on its sign.
    circuit_toggle,        ///< Along a circuit: dyad `group` is at a toggle; the input reverses, the dyad's sign changes.
  };
  Kind kind = Kind::none;
  std::uint32_t group = 0;      ///< group_open: the equation group that stays open; dyad_open, circuit_toggle: the
                                ///< dyad; point_undefined: the point.
  bool from_guesses = true;     ///< group_open: Newton started from the guesses (else the last assembled position).
  double from = 0;              ///< branch_stops: the input continued from (SI).
  double stopped_at = 0;        ///< branch_stops: where the motion stops (SI).
  double residual = 0;          ///< group_open: max |Phi| after Newton (m).
};

}  // namespace kinema
