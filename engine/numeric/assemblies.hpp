// Which of its two assemblies each dyad of a joints-and-links mechanism is on: the
// sketch's, or the one its inner joint states ("left of B-D": the side of the line from
// joint B to joint D it is on at the driver's sketch value). Read from the closed-form
// positions at the sketch; the unknowns' guesses follow the stated assemblies.
#pragma once

#include "engine/constraints/constraint_system.hpp"

namespace kinema {

/// Sets each dyad's sign in system.plan (a plan solved in closed form; others are left as
/// they are) and the unknowns' guesses of stated assemblies. Throws InputError (at the
/// joint that states it) for an assembly that chooses neither or both, or that does not
/// close at the driver's sketch value.
void settle_assemblies(ConstraintSystem& system);

}  // namespace kinema
