// A spatial chain drawn in 3-D with tikz-3dplot (Debian's texlive-pictures): the
// observer's axes, each frame's origin joined to its parent's and its axes as a small
// triad, the points joined to their frames' origins, and the points' velocities as red
// arrows, all at one solved position, to a stated scale. Needs \usepackage{tikz-3dplot}.
#pragma once

#include <ostream>

#include "engine/constraint_system.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

/// The chain with its frames where the analysis placed them at `state` (placed_frames).
void write_tikz_chain(std::ostream& out, const ConstraintSystem& system, const std::vector<PlacedFrame>& frames,
                      const MotionState& state);

}  // namespace kinema
