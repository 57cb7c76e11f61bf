// Geometry for drawings: each term of each planar loop as a segment from the
// end of the terms before it, evaluated at a solved position with a compiled
// tape (no GiNaC per drawing), and classed as ground, link or slider.
#pragma once

#include <complex>
#include <vector>

#include <kinema/engine/constraint_system.hpp>
#include <kinema/engine/numeric/motion_table.hpp>
#include <kinema/engine/numeric/tape.hpp>

namespace kinema {

struct DrawingSegment {
  enum class Kind { ground, link, slider };
  std::complex<double> from, to;  ///< SI.
  Kind kind = Kind::link;
};

class MechanismGeometry {
 public:
  explicit MechanismGeometry(const ConstraintSystem& system);
  /// The loops' segments at a state whose position is known (status not unassembled).
  std::vector<DrawingSegment> segments(const MotionState& state) const;

 private:
  CompiledExpressions tape_;  ///< Inputs: parameters, input, q; outputs: x, y of each term.
  std::vector<double> parameter_values_;
  std::vector<std::size_t> loop_term_count_;  ///< Terms of each loop, in order.
  std::vector<DrawingSegment::Kind> kinds_;
};

}  // namespace kinema
