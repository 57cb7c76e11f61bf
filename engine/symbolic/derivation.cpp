#include <kinema/engine/symbolic/derivation.hpp>

#include <set>

#include <kinema/engine/errors.hpp>
#include <kinema/engine/symbolic/trig_simplify.hpp>

namespace kinema {
namespace {

using GiNaC::ex;

// Splits loops into blocks that can be solved one after another.
std::vector<RateBlock> find_blocks(const LoopClosure& closure) {
  const std::size_t loop_count = closure.loop_vectors.size();
  std::vector<std::set<std::size_t>> loop_unknowns(loop_count);
  for (std::size_t row = 0; row < closure.equations.size(); ++row)
    for (std::size_t j = 0; j < closure.unknowns.size(); ++j)
      if (closure.equations[row].has(closure.unknowns[j]))
        loop_unknowns[closure.equation_loop[row]].insert(j);

  std::vector<RateBlock> blocks;
  std::vector<bool> loop_done(loop_count, false);
  std::set<std::size_t> solved;
  bool progress = true;
  while (progress) {
    progress = false;
    for (std::size_t k = 0; k < loop_count; ++k) {
      if (loop_done[k]) continue;
      std::vector<std::size_t> fresh;
      for (std::size_t j : loop_unknowns[k])
        if (!solved.count(j)) fresh.push_back(j);
      if (fresh.size() != 2) continue;
      RateBlock block;
      block.loops = {k};
      block.equations = {2 * k, 2 * k + 1};
      block.unknowns = fresh;
      for (std::size_t j : fresh) solved.insert(j);
      loop_done[k] = true;
      blocks.push_back(block);
      progress = true;
      break;  // restart so that blocks follow the file order where possible
    }
  }
  // Whatever is coupled is solved together.
  RateBlock rest;
  for (std::size_t k = 0; k < loop_count; ++k) {
    if (loop_done[k]) continue;
    rest.loops.push_back(k);
    rest.equations.push_back(2 * k);
    rest.equations.push_back(2 * k + 1);
  }
  for (std::size_t j = 0; j < closure.unknowns.size(); ++j)
    if (!solved.count(j)) rest.unknowns.push_back(j);
  if (!rest.loops.empty()) {
    if (rest.unknowns.size() != rest.equations.size()) {
      // Not separable in this order: solve the whole system at once.
      RateBlock all;
      for (std::size_t k = 0; k < loop_count; ++k) {
        all.loops.push_back(k);
        all.equations.push_back(2 * k);
        all.equations.push_back(2 * k + 1);
      }
      for (std::size_t j = 0; j < closure.unknowns.size(); ++j) all.unknowns.push_back(j);
      return {all};
    }
    blocks.push_back(rest);
  }
  return blocks;
}

// Cramer's rule on block rows/columns, each ratio simplified the textbook way.
std::vector<ex> solve_block(const GiNaC::matrix& jacobian, const RateBlock& block,
                            const std::vector<ex>& right_hand_side) {
  const std::size_t k = block.unknowns.size();
  GiNaC::matrix a(k, k);
  for (std::size_t r = 0; r < k; ++r)
    for (std::size_t c = 0; c < k; ++c) a(r, c) = jacobian(block.equations[r], block.unknowns[c]);
  const ex determinant = a.determinant(GiNaC::determinant_algo::laplace);
  std::vector<ex> solution;
  for (std::size_t c = 0; c < k; ++c) {
    GiNaC::matrix replaced = a;
    for (std::size_t r = 0; r < k; ++r) replaced(r, c) = right_hand_side[r];
    solution.push_back(simplify_ratio(replaced.determinant(GiNaC::determinant_algo::laplace), determinant));
  }
  return solution;
}

}  // namespace

std::string default_rate_name(const std::string& coordinate, int order) {
  for (const char* angle : {"theta", "phi"}) {
    const std::string prefix(angle);
    if (coordinate.size() > prefix.size() && coordinate.compare(0, prefix.size(), prefix) == 0) {
      return (order == 1 ? "omega" : "alpha") + coordinate.substr(prefix.size());
    }
  }
  return coordinate + (order == 1 ? "_dot" : "_ddot");
}

GiNaC::ex Derivation::time_derivative(const GiNaC::ex& e) const {
  ex result = e.diff(closure.input) * input_rate + e.diff(input_rate) * input_second_rate;
  for (std::size_t j = 0; j < closure.unknowns.size(); ++j) {
    result += e.diff(closure.unknowns[j]) * rates[j] + e.diff(rates[j]) * second_rates[j];
  }
  return result;
}

Derivation derive(const Mechanism& mechanism, const LoopClosure& closure) {
  Derivation d;
  d.closure = closure;
  const std::size_t n = closure.unknowns.size();

  // Rate names: the file's, else the textbook's (omega3, alpha3), unless that clashes.
  std::set<std::string> taken;
  for (const auto& p : mechanism.parameters) taken.insert(p.name);
  taken.insert(mechanism.input.name);
  for (const auto& u : mechanism.unknowns) taken.insert(u.name);
  auto pick = [&](const std::string& given, const std::string& coordinate, int order,
                  const SourceLocation& where) {
    std::string name = given.empty() ? default_rate_name(coordinate, order) : given;
    if (taken.count(name)) {
      if (!given.empty()) {
        throw InputError(where.str() + ": rate name \"" + name + "\" of \"" + coordinate +
                         "\" is already used; choose another");
      }
      name = coordinate + (order == 1 ? "_dot" : "_ddot");
    }
    taken.insert(name);
    return GiNaC::realsymbol(name);
  };
  d.input_rate = pick(mechanism.input.rate_name, mechanism.input.name, 1, mechanism.input.where);
  d.input_second_rate =
      pick(mechanism.input.second_rate_name, mechanism.input.name, 2, mechanism.input.where);
  for (const Unknown& u : mechanism.unknowns) {
    d.unknown_names.push_back(u.name);
    d.rates.push_back(pick(u.rate_name, u.name, 1, u.where));
    d.second_rates.push_back(pick(u.second_rate_name, u.name, 2, u.where));
  }

  d.jacobian = GiNaC::matrix(n, n);
  d.input_jacobian = GiNaC::matrix(n, 1);
  for (std::size_t i = 0; i < n; ++i) {
    const ex& phi = closure.equations[i];
    for (std::size_t j = 0; j < n; ++j) d.jacobian(i, j) = phi.diff(closure.unknowns[j]);
    d.input_jacobian(i, 0) = phi.diff(closure.input);
    d.velocity_equations.push_back(d.time_derivative(phi));
    d.acceleration_equations.push_back(d.time_derivative(d.velocity_equations.back()).expand());
    GiNaC::exmap no_second_rates;
    for (const auto& s : d.second_rates) no_second_rates[s] = 0;
    d.acceleration_rhs.push_back((-d.acceleration_equations.back().subs(no_second_rates)).expand());
  }

  d.blocks = find_blocks(closure);
  d.solved_rates.assign(n, 0);
  d.solved_second_rates.assign(n, 0);
  std::vector<bool> solved(n, false);
  for (const RateBlock& block : d.blocks) {
    std::vector<ex> velocity_rhs, acceleration_rhs;
    for (std::size_t row : block.equations) {
      ex v = -d.input_jacobian(row, 0) * d.input_rate;
      ex a = d.acceleration_rhs[row];
      for (std::size_t j = 0; j < n; ++j) {
        if (!solved[j]) continue;
        v -= d.jacobian(row, j) * d.rates[j];
        a -= d.jacobian(row, j) * d.second_rates[j];
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

  for (std::size_t p = 0; p < closure.point_x.size(); ++p) {
    d.point_velocity_x.push_back(d.time_derivative(closure.point_x[p]));
    d.point_velocity_y.push_back(d.time_derivative(closure.point_y[p]));
    d.point_acceleration_x.push_back(d.time_derivative(d.point_velocity_x.back()));
    d.point_acceleration_y.push_back(d.time_derivative(d.point_velocity_y.back()));
  }
  return d;
}

}  // namespace kinema
