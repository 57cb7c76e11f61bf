// Velocities and accelerations of a joints-and-links mechanism written the way the
// seeds work them out, group by group in solving order (driver, then each dyad):
//  - relative velocity (seed 004): the middle joint's velocity from each side,
//    v_C = v_B + omega2 x r_BC = v_D + omega3 x r_DC (a slider adds its relative
//    velocity, and in accelerations its Coriolis term 2 omega x v_rel), the two
//    components solved for the dyad's two rates;
//  - joint coordinates (seed 002, sections 4.2-4.6): the middle joint's coordinates
//    bound by each side (a circle about a pin, (4.42); a line of a guide, (4.51)),
//    differentiated in time ((4.43), (4.45)) and solved for its velocity and
//    acceleration, then each link's omega and alpha from its joints.
// Every relation is a GiNaC equation in symbols named after the joints (x_C, v_Cx,
// a_Cx) and the rates of the loops' coordinates, so that it can be checked by meaning.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/constraint_system.hpp"
#include "engine/symbolic/dyad_derivation_types.hpp"

namespace kinema {

/// The relations of every group of a joints-and-links system solved in closed form;
/// InputError for any other system (vector loops, or links that form no dyad).
DyadDerivation derive_by_dyads(const ConstraintSystem& system, DerivationMethod method);

/// InputError (what the file is, and that --method loops works for every file) unless
/// `method` is loops or the system is joints and links solved dyad by dyad.
void check_method_applies(const ConstraintSystem& system, DerivationMethod method);

}  // namespace kinema
