#include "engine/analysis/diagnostics.hpp"

#include <cmath>

#include "engine/base/number_format.hpp"
#include "engine/numeric/solver.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/structure.hpp"

namespace kinema {

std::string describe_input(const ConstraintSystem& system, double input) {
  const OutputScale scale(system);
  return system.input.name + " = " + format_significant(scale.input(input)) + " " +
         scale.coordinate_unit(system.input.dimension);
}

namespace {

// The largest continuation step in words (as Kinematics sets it).
std::string describe_step(const ConstraintSystem& system) {
  if (system.input.dimension == Dimension::angle) return "2 deg";
  if (system.input.dimension == Dimension::time) return "0.01 s";
  return format_significant(0.01 * system.length_scale / system.output.length_factor) + " " + system.output.length;
}

}  // namespace

std::string describe_failure(const ConstraintSystem& system, double input, const Failure& failure) {
  using Kind = Failure::Kind;
  switch (failure.kind) {
    case Kind::none: return "";
    case Kind::resumed_after_gap:
      return "resumed after positions that could not be assembled; the branch across the gap is not guaranteed";
    case Kind::group_open:
      if (!std::isfinite(failure.residual)) {  // not a gap to print: the equations gave no number
        return system.describe_group(failure.group) + " cannot be evaluated at " + describe_input(system, input) +
               ": its equations do not give finite numbers there (an angle or length past the range of the "
               "arithmetic, or a division by zero); choose another input value";
      }
      return system.describe_group(failure.group) + " cannot be closed at " + describe_input(system, input) +
             ": the links do not reach (loop gap " +
             format_significant(failure.residual / system.output.length_factor) + " " + system.output.length +
             " after Newton-Raphson from the " + (failure.from_guesses ? "guesses" : "last assembled position") +
             "); choose another input value, or check the lengths and the guesses";
    case Kind::branch_stops:
      return describe_input(system, input) + " cannot be reached from " + describe_input(system, failure.from) +
             " on the same assembly branch: the motion stops near " + describe_input(system, failure.stopped_at) +
             " (a limit or toggle position)";
    case Kind::too_far:
      return describe_input(system, input) + " cannot be reached from " + describe_input(system, failure.from) +
             " by continuation: they are more than " + format_significant(solver::kMaxContinuationSteps) +
             " steps apart (a step is at most " + describe_step(system) +
             "), or too large for a step to change them; give values closer together";
    case Kind::singular_jacobian:
      return "singular position at " + describe_input(system, input) +
             ": the Jacobian Phi_q is rank-deficient (toggle or dead-centre position), so "
             "velocities and accelerations are not defined there; choose a nearby value";
    case Kind::dyad_open:
      return (system.linkage ? describe_dyad(*system.linkage, failure.group) : "a dyad") + " cannot close at " +
             describe_input(system, input) +
             ": its links do not reach on the assembly of the sketch; choose another input value, or check the lengths";
    case Kind::circuit_toggle:
      return (system.linkage ? describe_dyad(*system.linkage, failure.group) : "a dyad") + " is at a toggle at " +
             describe_input(system, input) +
             " (its links in line): the input reverses here and the dyad changes assembly; velocities and "
             "accelerations are not defined at the toggle itself";
    case Kind::point_undefined: {
      const PointObservable& point = system.points.at(failure.group);
      return (point.is_joint ? "joint \"" : "point \"") + point.name + "\" (" + point.where.str() +
             ") has no value at " + describe_input(system, input) +
             ": its formula gives no real number there (the square root or logarithm of a negative number, or a "
             "division by zero), though the position and rates are defined; choose another value, or check the "
             "point's formula";
    }
    case Kind::nonfinite_rates:
      return "non-finite rates at " + describe_input(system, input) +
             " (a formula divides by zero or overflows there); choose a nearby value, or check the sizes of the file's numbers";
  }
  return "";
}

}  // namespace kinema
