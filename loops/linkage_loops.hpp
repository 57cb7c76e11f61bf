// The joints-and-links front end: a mechanism described as drawn (pins and
// sliders at sketch positions, links listing their joints, a driver) is written as
// the vector loops a student would write by hand, so that everything downstream —
// derivation, the compiled evaluator, every printer — is the vector-loop pipeline's.
//
// The link graph (ground and links as nodes, joints as edges) is checked for
// connectivity and mobility (Grübler), a spanning tree from ground places every link,
// and each joint outside the tree closes one independent loop. Every moving link gets
// an angle (the direction from its first joint to its second), every slider a
// coordinate along its line; their sketch values are the guesses, so the assembly
// branch is the sketch's.
#pragma once

#include <string>

#include "loops/mechanism.hpp"

namespace kinema {

/// Fills mechanism.parameters (lengths, offsets and positions the loops need, after the
/// file's own), input.name, unknowns, loops and points from mechanism.linkage. Throws
/// InputError naming file:line, the joints and links, and what to change.
void linkage_loops(Mechanism& mechanism);

/// The mechanism as a vector-loop file (TOML) that kinema reads to the same numbers.
std::string vector_loop_file(const Mechanism& mechanism);

}  // namespace kinema
