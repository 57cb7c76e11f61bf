// A TikZ drawing of a planar mechanism at one solved position: links, ground
// hatching, slider blocks and guides, the named points with their velocity
// vectors to a stated scale.
#pragma once

#include <ostream>

#include "engine/constraints/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/analysis/analysis.hpp"

namespace kinema {

/// The drawing at `state` as the analysis found it there (its bodies, or its segments
/// and points on links numbered by `link_labels`); without `arrows` the points' velocity and
/// acceleration arrows are left out (a student's problem sheet, where they are the answers).
void write_tikz_mechanism(std::ostream& out, const ConstraintSystem& system, const ValueAnalysis& at,
                          const std::vector<std::string>& link_labels, const MotionState& state, bool arrows = true);

}  // namespace kinema
