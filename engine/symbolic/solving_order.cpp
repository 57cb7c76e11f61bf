#include "engine/symbolic/solving_order.hpp"

#include <set>

namespace kinema {

std::vector<SolvingBlock> solving_order(const ConstraintSystem& system) {
  const std::size_t group_count = system.groups.size();
  const std::size_t unknown_count = system.unknowns.size();
  std::vector<std::set<std::size_t>> group_unknowns(group_count);
  for (const Equation& equation : system.equations)
    for (std::size_t j = 0; j < unknown_count; ++j)
      if (equation.expression.has(system.unknowns[j].symbol)) group_unknowns[equation.group].insert(j);

  std::vector<SolvingBlock> blocks;
  std::vector<bool> group_done(group_count, false);
  std::set<std::size_t> solved;
  bool progress = true;
  while (progress) {
    progress = false;
    for (std::size_t k = 0; k < group_count; ++k) {
      if (group_done[k]) continue;
      std::vector<std::size_t> fresh;
      for (std::size_t j : group_unknowns[k])
        if (!solved.count(j)) fresh.push_back(j);
      if (fresh.size() != system.groups[k].equations.size()) continue;
      blocks.push_back({{k}, system.groups[k].equations, fresh});
      for (std::size_t j : fresh) solved.insert(j);
      group_done[k] = true;
      progress = true;
      break;  // restart so that blocks follow the file order where possible
    }
  }
  // Whatever is coupled is solved together.
  SolvingBlock rest;
  for (std::size_t k = 0; k < group_count; ++k) {
    if (group_done[k]) continue;
    rest.groups.push_back(k);
    rest.equations.insert(rest.equations.end(), system.groups[k].equations.begin(), system.groups[k].equations.end());
  }
  for (std::size_t j = 0; j < unknown_count; ++j)
    if (!solved.count(j)) rest.unknowns.push_back(j);
  if (!rest.groups.empty()) {
    if (rest.unknowns.size() != rest.equations.size()) {
      // Not separable in this order: solve the whole system at once.
      SolvingBlock all;
      for (std::size_t k = 0; k < group_count; ++k) {
        all.groups.push_back(k);
        all.equations.insert(all.equations.end(), system.groups[k].equations.begin(), system.groups[k].equations.end());
      }
      for (std::size_t j = 0; j < unknown_count; ++j) all.unknowns.push_back(j);
      return {all};
    }
    blocks.push_back(rest);
  }
  return blocks;
}

}  // namespace kinema
