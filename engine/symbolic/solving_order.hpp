// Solving order: which unknowns can be found from which equation groups one
// block after another (loop ABCD gives theta3, theta4; then loop ...), as a
// worked solution proceeds. Reads the equations' group labels only.
#pragma once

#include <cstddef>
#include <vector>

#include "engine/constraints/constraint_system.hpp"

namespace kinema {

/// Unknowns solved together from a set of equation groups.
struct SolvingBlock {
  std::vector<std::size_t> groups;     ///< Indices into ConstraintSystem::groups.
  std::vector<std::size_t> equations;  ///< Rows of Phi.
  std::vector<std::size_t> unknowns;   ///< Columns of Phi_q.
};

/// Groups whose equations hold exactly as many new unknowns as equations are
/// taken one at a time, in file order where possible; whatever stays coupled is
/// one last block (or, when that is not square, the whole system is one block).
std::vector<SolvingBlock> solving_order(const ConstraintSystem& system);

}  // namespace kinema
