#include "engine/constraints/constraint_system.hpp"

#include "engine/base/errors.hpp"

namespace kinema {

void refuse_unknown_count(std::size_t count, const SourceLocation& first_past, const std::string& name) {
  throw InputError(first_past.str() + ": unknown \"" + name + "\": the mechanism has " + std::to_string(count) +
                   " unknowns, and kinema solves up to " + std::to_string(kMaxUnknowns) +
                   " in one system (its solver is dense: the time per position grows as the cube of the count); "
                   "split the file into mechanisms that do not share unknowns");
}

}  // namespace kinema
