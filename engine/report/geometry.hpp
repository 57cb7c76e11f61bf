// Geometry for drawings: each term of each planar loop as a segment from the
// end of the terms before it, evaluated at a solved position with a compiled
// tape (no GiNaC per drawing), and classed as ground, link or slider.
#pragma once

#include <complex>
#include <optional>
#include <string>
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

/// A joints-and-links mechanism as drawn: its links with their joints where they are,
/// ground pivots and fixed guides (SI, world positions).
struct LinkageDrawing {
  struct Joint {
    std::string name;
    std::complex<double> at;
  };
  struct Link {
    std::vector<Joint> joints;
    bool block = false;  ///< A slider block (drawn as a block turned by `angle`).
    double angle = 0;
  };
  struct Guide {
    std::complex<double> through, along;  ///< A point of a fixed guide line and its unit direction.
  };
  std::vector<Link> links;
  std::vector<Joint> ground_pivots;
  std::vector<Guide> guides;
};

/// The drawing at a state whose position is known, for a joints-and-links mechanism
/// placed in closed form; nullopt for anything else.
std::optional<LinkageDrawing> linkage_drawing(const ConstraintSystem& system, const MotionState& state);

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
