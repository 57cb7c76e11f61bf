// The instant centres of a planar mechanism drawn over its links in TikZ
// (the Kennedy lines that fix each secondary centre dashed, centres at infinity as
// arrows in their direction), with a table of the centres and one of the
// angular-velocity ratios they give beside the solved ones.
#pragma once

#include <ostream>

#include "engine/constraints/constraint_system.hpp"
#include "engine/numeric/motion_table.hpp"
#include "engine/analysis/analysis.hpp"

namespace kinema {

/// The instant centres of one value (`at`, analysed): a figure with the Kennedy lines, the
/// table of every pair of bodies, the velocity ratios the centres give.
void write_tikz_instant_centres(std::ostream& out, const ConstraintSystem& system, const ValueAnalysis& at,
                                const InstantCentres& centres);

}  // namespace kinema
