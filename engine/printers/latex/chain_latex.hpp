// A spatial chain worked out at the instant (engine/analysis/chain_instant) as rows of an
// amsmath align*, the way seed 000 writes it: each angular velocity as the sum of the
// relative turnings about unit axes, then its components and numbers; each point's v and
// a term by term, the results boxed. Shared by `derive --format latex` and `kinema latex`.
#pragma once

#include <vector>

#include "engine/constraint_system.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/analysis/chain_instant.hpp"

namespace kinema {

/// The frames' rows (angular velocities and accelerations).
std::vector<LatexRow> chain_frame_rows(const ChainAtInstant& chain, const TextbookForm& form,
                                       double budget = kLatexLineBudget);
/// The points' rows (velocities, then accelerations, of each point). Each result carries
/// a "% kinema vector: v_B = [x, y, z]" comment in GiNaC syntax.
std::vector<LatexRow> chain_point_rows(const ChainAtInstant& chain, const TextbookForm& form,
                                       double budget = kLatexLineBudget);
/// "at the instant t = 0: theta_1 = 0 deg, ...; components along the axes of E0" (text).
std::string chain_instant_latex(const ConstraintSystem& system, const ChainAtInstant& chain);

}  // namespace kinema
