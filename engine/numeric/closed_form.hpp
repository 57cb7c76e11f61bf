// Joints and links solved in closed form (engine/numeric/dyad_positions) as the unknowns of the
// compiled model: what the sweep and the circuit place a row with.
#pragma once

#include <Eigen/Dense>

#include <cstdint>
#include <vector>

#include "engine/constraints/solving_plan.hpp"

namespace kinema {

/// The position at `input`, dyad by dyad, on `signs` (empty: the sketch's); false, with
/// the dyad that cannot close, where one cannot. Link angles are taken the whole turns
/// nearest q's (the last position known), so that a run's angles do not wrap.
bool closed_form_position(const SolvingPlan& frames, double input, const std::vector<int>& signs,
                          Eigen::VectorXd& q, std::uint32_t& dyad);

}  // namespace kinema
