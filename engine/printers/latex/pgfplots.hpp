// pgfplots of a run over the input's range: the unknowns, their rates and
// second rates, and the points' speeds, with gaps where the mechanism cannot
// be assembled and singular positions marked.
#pragma once

#include <ostream>

#include "engine/constraints/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"

namespace kinema {

void write_pgfplots(std::ostream& out, const ConstraintSystem& system, const MotionTable& sweep);

}  // namespace kinema
