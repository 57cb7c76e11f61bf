#include "engine/constraints/constraint_system.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/errors.hpp"

namespace kinema {

double length_scale_of(const std::vector<SystemParameter>& parameters) {
  double largest = 0;
  for (const SystemParameter& p : parameters)
    if (p.sets_length_scale) largest = std::max(largest, std::fabs(p.value));
  return largest > 0 ? largest : 1.0;
}

std::size_t written_parameter_index(const ConstraintSystem& system, const std::string& name) {
  std::string names;
  bool made = false;  // one kinema made (a joints file's sketch numbers, a chain's starting motion)
  for (std::size_t i = 0; i < system.parameters.size(); ++i) {
    const SystemParameter& p = system.parameters[i];
    if (!p.written) {
      made = made || p.symbol.get_name() == name;
      continue;
    }
    if (p.symbol.get_name() == name) return i;
    names += (names.empty() ? "" : ", ") + p.symbol.get_name();
  }
  throw InputError(system.source_file + ": no parameter named \"" + name + "\"" +
                   (made ? " that the file writes: kinema made it from the file (its sketch or starting motion), and "
                           "only the file's own parameters take other values"
                         : "") +
                   " (there are: " + (names.empty() ? "none" : names) + ")");
}

void refuse_unknown_count(std::size_t count, const SourceLocation& first_past, const std::string& name) {
  throw InputError(first_past.str() + ": unknown \"" + name + "\": the mechanism has " + std::to_string(count) +
                   " unknowns, and kinema solves up to " + std::to_string(kMaxUnknowns) +
                   " in one system (its solver is dense: the time per position grows as the cube of the count); "
                   "split the file into mechanisms that do not share unknowns");
}

}  // namespace kinema
