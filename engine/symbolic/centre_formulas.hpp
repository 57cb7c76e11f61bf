// The instant centres of a planar loop system (a vector-loop file's, or the loops kinema
// finds for a joints-and-links file) as formulas of the model's tape inputs, put on
// its drawing stage when the model is compiled (TapeLayout::centre_body_output,
// centre_pair_output place them): the analysis reads its centres there, and a page whose sliders
// solve again runs the same formulas for other dimensions. Nothing here runs per state.
#pragma once

#include <vector>

#include <ginac/ginac.h>

#include "engine/constraints/constraint_system.hpp"
#include "engine/symbolic/centre_body.hpp"
#include "engine/symbolic/derivation.hpp"

namespace kinema {

/// The formulas as TapeLayout places them, for the bodies of a vector-loop file found with
/// a point of known velocity on them (`bodies`, set here): a link by a named
/// point on it, else by a term of it between two known points (named points, or ground
/// ones: the origin and the ends of a loop's ground terms), a slider's guide link by its
/// pivot, a slider's block by its sliding point. A joints-and-links file's bodies also
/// say which of its SolvingPlan's bodies they are (CentreBody::plan_body): a link by the
/// coordinate whose rate it turns at, a block (at rest or turning with its guide, as ground
/// and the guide do) by its sliding point, the slider's joint. Empty (and no bodies) for a
/// spatial chain.
std::vector<GiNaC::ex> centre_stage(const ConstraintSystem& system, const Derivation& derivation,
                                    std::vector<CentreBody>& bodies);

}  // namespace kinema
