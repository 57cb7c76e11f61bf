#include "engine/symbolic/derivation.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/constraints/differentiate.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/symbolic/trig_simplify.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

// The symbols d/dt differentiates through: the driver, the unknowns and their rates.
GiNaC::exset moving_symbols(const ConstraintSystem& system) {
  GiNaC::exset moving{system.input.symbol, system.input.rate};
  for (const Coordinate& q : system.unknowns) moving.insert({q.symbol, q.rate});
  return moving;
}

// d/dt e, refused (as bad input) when it would be larger than the budget.
ex bounded_time_derivative(const ConstraintSystem& system, const GiNaC::exset& moving, const ex& e,
                           const std::string& what, const char* formula) {
  check_derivative_size(e, moving, what, formula);
  return time_derivative(system, e);
}

// The determinant by cofactors along the first row, left as it comes out.
ex cofactor_determinant(const GiNaC::matrix& a) {
  const unsigned k = a.rows();
  if (k == 1) return a(0, 0);
  ex sum = 0;
  for (unsigned c = 0; c < k; ++c) {
    if (a(0, c).is_zero()) continue;
    GiNaC::matrix minor(k - 1, k - 1);
    for (unsigned r = 1; r < k; ++r)
      for (unsigned j = 0, m = 0; j < k; ++j)
        if (j != c) minor(r - 1, m++) = a(r, j);
    sum += (c % 2 == 0 ? 1 : -1) * a(0, c) * cofactor_determinant(minor);
  }
  return sum;
}

// The terms of a determinant multiplied out, at most (the permanent of its entries'
// counts), by cofactors of the counts; 0 for a block past 8 unknowns, whose cofactors are
// too many to count (the samples' blocks have 2).
double determinant_terms_estimate(const std::vector<std::vector<double>>& counts, std::vector<bool>& used,
                                  std::size_t row) {
  if (row == counts.size()) return 1;
  double terms = 0;
  for (std::size_t c = 0; c < counts.size() && terms <= kMultiplyOutBudget; ++c) {
    if (used[c] || counts[row][c] == 0) continue;
    used[c] = true;
    terms += counts[row][c] * determinant_terms_estimate(counts, used, row + 1);
    used[c] = false;
  }
  return terms;
}

bool multiplies_out(const GiNaC::matrix& a) {
  const std::size_t k = a.rows();
  if (k > 8) return false;
  std::vector<std::vector<double>> counts(k, std::vector<double>(k));
  for (std::size_t r = 0; r < k; ++r)
    for (std::size_t c = 0; c < k; ++c)
      counts[r][c] = a(r, c).is_zero() ? 0 : expanded_terms_estimate(a(r, c), kMultiplyOutBudget);
  std::vector<bool> used(k, false);
  return determinant_terms_estimate(counts, used, 0) > kMultiplyOutBudget;
}

// True when calls of functions whose derivatives divide (log, tan, sqrt, atan2, ...: not
// sin, cos, exp) hold each other `levels` deep (log(10 + log(10 + ...))).
bool nests_functions(const ex& e, int levels) {
  if (levels <= 0) return true;
  bool dividing = GiNaC::is_a<GiNaC::function>(e);
  if (dividing) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    dividing = name != "sin" && name != "cos" && name != "exp";
  }
  for (std::size_t i = 0; i < e.nops(); ++i)
    if (nests_functions(e.op(i), dividing ? levels - 1 : levels)) return true;
  return false;
}

// Functions whose derivatives divide, nested this deep in a block's entries: GiNaC's
// determinant normalises its result, expanding the quotients the chain rule makes of them
// (log nested 8 deep in a loop never finished deriving, 6 deep took 5 s); such a block is
// solved by cofactors and its ratio left unsimplified. The samples nest none of them.
constexpr int kPlainSolveNesting = 4;

// Cramer's rule on block rows/columns, each ratio simplified the textbook way.
// A block whose Jacobian vanishes identically cannot give its unknowns at any position
// (they are not independent: only their sum appears, say). Said as bad input.
void check_independent(const ConstraintSystem& system, const GiNaC::matrix& jacobian, const SolvingBlock& block) {
  const std::size_t k = block.unknowns.size();
  GiNaC::matrix a(k, k);
  for (std::size_t r = 0; r < k; ++r)
    for (std::size_t c = 0; c < k; ++c) a(r, c) = jacobian(block.equations[r], block.unknowns[c]);
  // Past the simplification budget the check is left to the numbers (every row singular);
  // GiNaC's determinant multiplies out (tan nested 16 deep: 2^16 terms and more) and
  // normalises (log nested 32 deep never loaded).
  if (multiplies_out(a) || nests_functions(a, kPlainSolveNesting)) return;
  const ex determinant = a.determinant(GiNaC::determinant_algo::laplace);
  if (expression_size(determinant) > kSimplifyBudget) return;
  if (!combine_trig_products(determinant.normal().numer()).is_zero()) return;
  std::string groups, unknowns;
  for (std::size_t g : block.groups)
    groups += (groups.empty() ? "" : ", ") + system.groups[g].where.str() + ": " + system.groups[g].kind + " \"" +
              system.groups[g].name + "\"";
  for (std::size_t j : block.unknowns) unknowns += (unknowns.empty() ? "" : ", ") + system.unknowns[j].name;
  throw InputError(groups + ": the unknowns " + unknowns +
                   " cannot be found from it: the Jacobian is singular at every position, so they are not "
                   "independent (e.g. only their sum appears); write the loop with independent coordinates");
}

std::vector<ex> solve_block(const GiNaC::matrix& jacobian, const SolvingBlock& block,
                            const std::vector<ex>& right_hand_side) {
  const std::size_t k = block.unknowns.size();
  GiNaC::matrix a(k, k);
  bool nested = false;
  for (std::size_t r = 0; r < k; ++r) {
    nested = nested || nests_functions(right_hand_side[r], kPlainSolveNesting);
    for (std::size_t c = 0; c < k; ++c) {
      a(r, c) = jacobian(block.equations[r], block.unknowns[c]);
      nested = nested || nests_functions(a(r, c), kPlainSolveNesting);
    }
  }
  std::vector<GiNaC::matrix> numerators(k, a);
  for (std::size_t c = 0; c < k; ++c)
    for (std::size_t r = 0; r < k; ++r) numerators[c](r, c) = right_hand_side[r];
  // Determinants that would multiply out past the budget are left as cofactors too.
  nested = nested || multiplies_out(a) || std::any_of(numerators.begin(), numerators.end(), multiplies_out);
  const ex determinant = nested ? cofactor_determinant(a) : a.determinant(GiNaC::determinant_algo::laplace);
  std::vector<ex> solution;
  for (std::size_t c = 0; c < k; ++c) {
    const GiNaC::matrix& replaced = numerators[c];
    solution.push_back(nested ? cofactor_determinant(replaced) / determinant
                              : simplify_ratio(replaced.determinant(GiNaC::determinant_algo::laplace), determinant));
  }
  return solution;
}

// The rates and second rates in closed form, block by block in solving order (as a
// textbook solves them), from the Jacobian, gamma and the rates of earlier blocks.
void solve_rates(const ConstraintSystem& system, Derivation& d) {
  const std::size_t n = system.unknowns.size();
  d.solved_rates.assign(n, 0);
  d.solved_second_rates.assign(n, 0);
  std::vector<bool> solved(n, false);
  for (const SolvingBlock& block : d.blocks) {
    std::vector<ex> velocity_rhs, acceleration_rhs;
    for (std::size_t row : block.equations) {
      ex v = -d.input_jacobian(row, 0) * system.input.rate;
      ex a = d.acceleration_rhs[row];
      for (std::size_t j = 0; j < n; ++j) {
        if (!solved[j]) continue;
        v -= d.jacobian(row, j) * system.unknowns[j].rate;
        a -= d.jacobian(row, j) * system.unknowns[j].second_rate;
      }
      velocity_rhs.push_back(v);
      acceleration_rhs.push_back(a);
    }
    const auto rates = solve_block(d.jacobian, block, velocity_rhs);
    const auto second_rates = solve_block(d.jacobian, block, acceleration_rhs);
    for (std::size_t c = 0; c < block.unknowns.size(); ++c) {
      d.solved_rates[block.unknowns[c]] = rates[c];
      d.solved_second_rates[block.unknowns[c]] = second_rates[c];
      solved[block.unknowns[c]] = true;
    }
  }
}

// Terms r*exp(I*phi) of each loop with r and phi both moving.
std::vector<SlidingLinkTerms> sliding_links(const ConstraintSystem& system) {
  std::vector<SlidingLinkTerms> found;
  for (std::size_t k = 0; k < system.groups.size(); ++k) {
    if (!system.groups[k].vector) continue;
    const ex loop = system.groups[k].vector->expand();
    std::vector<ex> terms;
    if (GiNaC::is_a<GiNaC::add>(loop)) {
      for (const ex& t : loop) terms.push_back(t);
    } else {
      terms.push_back(loop);
    }
    for (const ex& term : terms) {
      if (!split_link_vector(term).polar) continue;
      const LinkVectorMotion m = link_vector_motion(system, term);
      if (m.length_rate.is_zero() || m.angle_rate.is_zero()) continue;
      const ex& length = m.link.length;
      found.push_back({k, length, m.link.angle, m.length_second_rate, m.length_rate * m.angle_rate,
                       length * m.angle_second_rate, length * m.angle_rate * m.angle_rate});
    }
  }
  return found;
}

}  // namespace

GiNaC::ex time_derivative(const ConstraintSystem& system, const GiNaC::ex& e) {
  std::vector<SymbolMotion> motions{{system.input.symbol, system.input.rate}, {system.input.rate, system.input.second_rate}};
  motions.reserve(2 * system.unknowns.size() + 2);
  for (const Coordinate& q : system.unknowns) {
    motions.push_back({q.symbol, q.rate});
    motions.push_back({q.rate, q.second_rate});
  }
  return time_derivative(e, motions);
}

Derivation derive(const ConstraintSystem& system, DerivationScope scope) {
  Derivation d;
  d.scope = scope;
  const bool full = scope == DerivationScope::full;
  const std::size_t n = system.unknowns.size();
  check_unknown_count(system.unknowns);
  const GiNaC::exset moving = moving_symbols(system);
  GiNaC::exmap no_second_rates;
  for (const Coordinate& q : system.unknowns) no_second_rates[q.second_rate] = 0;

  d.jacobian = GiNaC::matrix(n, n);
  d.input_jacobian = GiNaC::matrix(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const ex& phi = system.equations[i].expression;
    const GiNaC::exset symbols = symbols_of(phi);
    for (std::size_t j = 0; j < n; ++j)
      if (symbols.count(system.unknowns[j].symbol) != 0) d.jacobian(i, j) = partial(phi, system.unknowns[j].symbol);
    d.input_jacobian(i, 0) = partial(phi, system.input.symbol);
    const Equation& equation = system.equations[i];
    const EquationGroup& group = system.groups[equation.group];
    const std::string what = group.where.str() + ": " + group.kind + " \"" + group.name + "\" (" + equation.component + ")";
    d.velocity_equations.push_back(bounded_time_derivative(system, moving, phi, what, "velocity"));
    d.acceleration_equations.push_back(multiplied_out(
        bounded_time_derivative(system, moving, d.velocity_equations.back(), what, "acceleration")));
    d.acceleration_rhs.push_back(multiplied_out(-d.acceleration_equations.back().subs(no_second_rates)));
    if (full) d.acceleration_rhs_combined.push_back(combine_trig_products(d.acceleration_rhs.back()));
  }

  d.blocks = solving_order(system);
  for (const SolvingBlock& block : d.blocks) check_independent(system, d.jacobian, block);
  if (full) solve_rates(system, d);

  for (const PointObservable& point : system.points) {
    PointMotionFormulas motion;
    const std::string what = point.where.str() + ": point \"" + point.name + "\"";
    for (const ex& component : point.position) {
      motion.velocity.push_back(bounded_time_derivative(system, moving, component, what, "velocity"));
      motion.acceleration.push_back(bounded_time_derivative(system, moving, motion.velocity.back(), what, "acceleration"));
      if (full) motion.acceleration_combined.push_back(combine_trig_products(motion.acceleration.back()));
    }
    d.points.push_back(motion);
  }
  if (full) d.sliding_links = sliding_links(system);
  d.link_vectors = planar_link_vectors(system);
  return d;
}

const Derivation& full_derivation(const Derivation& derivation) {
  if (derivation.scope != DerivationScope::full) {
    throw std::logic_error("formulas printed from a derivation made for evaluation only; load the model with "
                           "DerivationScope::full");
  }
  return derivation;
}

}  // namespace kinema
