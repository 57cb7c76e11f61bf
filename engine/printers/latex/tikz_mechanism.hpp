// A TikZ drawing of a planar mechanism at one solved position: links, ground
// hatching, slider blocks and guides, the named points with their velocity
// vectors to a stated scale.
#pragma once

#include <ostream>

#include "engine/constraints/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/report/geometry.hpp"

namespace kinema {

void write_tikz_mechanism(std::ostream& out, const ConstraintSystem& system, const MechanismGeometry& geometry,
                          const MotionState& state);

}  // namespace kinema
