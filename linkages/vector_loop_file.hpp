// `kinema loops`: a planar mechanism as a vector-loop file (TOML) that kinema reads to
// the same numbers; a joints-and-links file as the loops its front end writes.
#pragma once

#include <string>

#include "engine/constraints/constraint_system.hpp"
#include "readers/mechanism.hpp"

namespace kinema {

/// The mechanism as written (`written`) as a vector-loop file, with the unknowns' guesses
/// of its constraint system (the assemblies the file states). InputError for a spatial chain.
std::string vector_loop_file(const Mechanism& written, const ConstraintSystem& system);

}  // namespace kinema
