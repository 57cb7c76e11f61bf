// A spatial chain drawn in 3-D with tikz-3dplot (Debian's texlive-pictures): the
// observer's axes, the chain's bodies (ChainBodies: ground pivots, each frame on its parent's
// body, the points on their frames' bodies, the couplers), each frame's axes as a small
// triad, and the points' velocities as red arrows, all at one solved position, to a stated
// scale, seen from the view that keeps its places apart (chain_view). Needs
// \usepackage{tikz-3dplot}.
#pragma once

#include <ostream>

#include "engine/constraints/constraint_system.hpp"
#include "engine/analysis/geometry.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

/// The chain with its frames where the analysis placed them at `state` (placed_frames).
void write_tikz_chain(std::ostream& out, const ConstraintSystem& system, const std::vector<PlacedFrame>& frames,
                      const MotionState& state);

}  // namespace kinema
