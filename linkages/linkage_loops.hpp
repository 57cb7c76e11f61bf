// The joints-and-links front end: a mechanism described as drawn (pins and
// sliders at sketch positions, links listing their joints, a driver) becomes the
// vector loops a student would write by hand, built as GiNaC expressions (the same
// constraint system as those loops written in a file: loops/planar_system builds both),
// with its solving plan (the dyads, engine/constraints/solving_plan.hpp).
//
// The link graph (ground and links as nodes, joints as edges) is checked for
// connectivity and mobility (Grübler), a spanning tree from ground places every link,
// and each joint outside the tree closes one independent loop. Every moving link gets
// an angle (the direction from its first joint to its second), every slider a
// coordinate along its line; their sketch values are the guesses, so the assembly
// branch is the sketch's.
#pragma once

#include "engine/constraints/constraint_system.hpp"
#include "engine/constraints/solving_plan.hpp"
#include "readers/mechanism.hpp"

namespace kinema {

/// A joints-and-links mechanism as vector loops, and how it is solved.
struct LinkageLoops {
  /// The file's as vector loops (no linkage): its parameters and those the loops need
  /// (lengths, offsets and positions, after the file's own), input, unknowns, loops, points.
  Mechanism loops;
  SolvingPlan plan;  ///< The dyads' assemblies not yet settled (engine/numeric/assemblies).
};

/// The loops as text, for `kinema loops` (linkages/vector_loop_file). Throws InputError
/// naming file:line, the joints and links, and what to change.
LinkageLoops linkage_loops(const Mechanism& written);

/// The constraint system of a joints-and-links mechanism: its loops' equations, with its
/// solving plan.
ConstraintSystem build_linkage_system(const Mechanism& written);

}  // namespace kinema
