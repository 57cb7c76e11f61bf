#include "loops/planar_system.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <utility>

#include "engine/base/errors.hpp"
#include "engine/base/naming.hpp"
#include "engine/constraints/complex_parts.hpp"
#include "engine/constraints/expression_parts.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

std::string context_of(const PlanarVector& v, const std::string& kind) {
  return v.where.str() + ": " + kind + " \"" + v.name + "\"";
}

// The x and y parts must be real functions the evaluator compiles: a function of a
// complex argument other than exp(I*...) (log(I*phi4) has the part log(abs(I*phi4)))
// does not separate so, and is refused here rather than failing in the compiler.
void check_separated(const ex& x, const ex& y, const std::string& formula, const std::string& context) {
  for (const ex& part : {x, y}) {
    bool separated = !part.has(GiNaC::I);
    for (auto it = part.preorder_begin(); separated && it != part.preorder_end(); ++it)
      separated = !GiNaC::is_a<GiNaC::function>(*it) || is_compiled_function(GiNaC::ex_to<GiNaC::function>(*it).get_name());
    if (!separated) {
      throw InputError(context + ": " + (formula.empty() ? "it" : "\"" + formula + "\"") +
                       " cannot be split into real x and y parts: only exp(I*angle) "
                       "may take a complex argument (not log(I*phi), say); write it by components, "
                       "{ x = \"...\", y = \"...\" }");
    }
  }
}

bool depends_on_unknowns(const ex& e, const ConstraintSystem& system) {
  for (const auto& q : system.unknowns)
    if (e.has(q.symbol)) return true;
  return false;
}

}  // namespace

PlanarSystemBuilder::PlanarSystemBuilder(const Mechanism& declarations) : declarations_(declarations) {
  // Before the loops are read: their checks grow with the square of the count.
  check_unknown_count(declarations_.unknowns);
  system_.title = declarations_.title;
  system_.description = declarations_.description;
  system_.source_file = declarations_.source_file;
  system_.output = declarations_.output;
  add_parameters();
  add_coordinates();
}

void PlanarSystemBuilder::add_loop(const PlanarVector& loop) {
  const ex x = real_part_of(loop.vector), y = imag_part_of(loop.vector);
  check_separated(x, y, loop.formula, context_of(loop, "loop"));
  add_loop(loop, x, y);
}

void PlanarSystemBuilder::add_loop(const PlanarVector& loop, const ex& x, const ex& y) {
  const std::string context = context_of(loop, "loop");
  check_length(loop.vector, context, "a loop is a sum of link vectors (lengths)");
  if (!depends_on_unknowns(x, system_) && !depends_on_unknowns(y, system_)) {
    throw InputError(context + " contains none of the unknowns; each loop must close "
                     "through at least one unknown coordinate");
  }
  EquationGroup group;
  group.kind = "loop";
  group.name = loop.name;
  group.where = loop.where;
  group.terms = loop.terms;
  group.vector = loop.vector;
  // The two rows of a planar loop: the only place that knows a loop is two equations.
  const std::size_t index = system_.groups.size();
  for (const auto& [component, expression] : {std::make_pair("x", x), std::make_pair("y", y)}) {
    group.equations.push_back(system_.equations.size());
    system_.equations.push_back({expression, index, component});
  }
  system_.groups.push_back(group);
}

void PlanarSystemBuilder::end_loops() {
  const std::size_t equations = system_.equations.size();
  const std::size_t unknowns = system_.unknowns.size();
  if (equations != unknowns) {
    // Where the count is passed: the first unknown without an equation, or the first
    // loop without unknowns.
    const SourceLocation where = unknowns > equations ? declarations_.unknowns[equations].where
                                                      : system_.groups[unknowns / 2].where;
    throw InputError(where.str() + ": " + std::to_string(system_.groups.size()) +
                     " loop(s) give " + std::to_string(equations) + " scalar equations, but there are " +
                     std::to_string(unknowns) + " unknowns (" + unknown_list() +
                     "); each vector loop closes two unknowns: add or remove a loop or an unknown");
  }
  for (std::size_t i = 0; i < unknowns; ++i) {
    bool used = false;
    for (const Equation& equation : system_.equations) used = used || equation.expression.has(system_.unknowns[i].symbol);
    if (!used) {
      throw InputError(declarations_.unknowns[i].where.str() + ": unknown \"" + declarations_.unknowns[i].name +
                       "\" appears in no loop");
    }
  }
}

void PlanarSystemBuilder::add_point(const PlanarVector& point) {
  const std::string context = context_of(point, "point");
  check_length(point.vector, context, "a point position must be a length (x + I*y)");
  PointObservable observable;
  observable.name = point.name;
  observable.where = point.where;
  observable.is_joint = point.is_joint;
  observable.components = {"x", "y"};
  observable.position = {real_part_of(point.vector), imag_part_of(point.vector)};
  check_separated(observable.position[0], observable.position[1], point.formula, context);
  observable.written = point.vector;
  observable.written_terms = point.terms;
  system_.points.push_back(observable);
}

ConstraintSystem PlanarSystemBuilder::system() && { return std::move(system_); }

// A loop or a point is a length, and uses no bare-number parameter as one.
void PlanarSystemBuilder::check_length(const ex& e, const std::string& context, const std::string& what) const {
  const auto power = LengthPower(powers_).of(e.expand(), context);
  if (power && *power != 1) {
    throw InputError(context + " is " + with_article(LengthPower::describe(*power)) + ", but " + what);
  }
  if (misuses_plain_numbers(e.expand(), true)) check_plain_numbers(e, context);
}

// Whether `e` (a length, or with length false anything) stops being one, or mixes
// units, once bare numbers count as of no length.
bool PlanarSystemBuilder::misuses_plain_numbers(const ex& e, bool length) const {
  if (plain_numbers_.empty()) return false;  // the common case
  try {
    const auto power = LengthPower(plain_powers_).of(e, "");
    return length && power && *power != 1;
  } catch (const InputError&) {
    return true;
  }
}

// Refuses the first bare-number parameter `e` uses, itself or through formulas of
// parameters, if `e` is to be a length: it was read as metres without a word.
void PlanarSystemBuilder::check_plain_numbers(const ex& e, const std::string& used_in) const {
  ex expanded = e;
  for (std::size_t k = 0; k < formulas_of_parameters_.size(); ++k) {
    const ex next = expanded.subs(formulas_of_parameters_);
    if (next.is_equal(expanded)) break;
    expanded = next;
  }
  for (const PlainNumber& p : plain_numbers_) {
    if (!expanded.has(p.symbol)) continue;
    throw InputError(p.where.str() + ": parameter \"" + p.name + "\" = \"" + p.text + "\" has no unit, and " +
                     used_in.substr(used_in.find(": ") + 2) + " (" + used_in.substr(0, used_in.find(": ")) +
                     ") uses it as a length; give its unit, e.g. \"" + p.text +
                     " m\" or \"" + p.text + " mm\" (a number without a unit is a ratio, as k in p = \"k*a\")");
  }
}

GiNaC::realsymbol PlanarSystemBuilder::symbol(const std::string& name, const std::string& latex) {
  GiNaC::realsymbol s(name, latex.empty() ? latex_symbol_name(name) : latex);
  formulas_.define(name, s);
  taken_.insert(name);
  return s;
}

// The file's rate name, else the textbook's (omega3, alpha3), else name_dot on a clash.
GiNaC::realsymbol PlanarSystemBuilder::rate_symbol(const std::string& given, const std::string& coordinate, int order,
                                                   const SourceLocation& where, const std::string& latex_coordinate) {
  std::string name = given.empty() ? default_rate_name(coordinate, order) : given;
  if (taken_.count(name)) {
    if (!given.empty()) {
      throw InputError(where.str() + ": rate name \"" + name + "\" of \"" + coordinate +
                       "\" is already used; choose another");
    }
    name = coordinate + (order == 1 ? "_dot" : "_ddot");
  }
  taken_.insert(name);
  // A coordinate with its own LaTeX name gets that name's dots.
  const std::string latex = latex_coordinate.empty() ? latex_symbol_name(name)
                                                     : (order == 1 ? "\\dot{" : "\\ddot{") + latex_coordinate + "}";
  return GiNaC::realsymbol(name, latex);
}

void PlanarSystemBuilder::add_coordinates() {
  const Input& input = declarations_.input;
  Driver& driver = system_.input;
  driver.name = input.name;
  driver.dimension = input.dimension;
  driver.symbol = symbol(input.name);
  driver.where = input.where;
  driver.values = input.values;
  driver.rate_value = input.rate;
  driver.second_rate_value = input.second_rate;
  driver.rate_text = input.rate_text;  // for documents: "60 rpm" as written
  driver.second_rate_text = input.second_rate_text;
  powers_[driver.symbol] = input.dimension == Dimension::length ? 1 : 0;
  for (const Unknown& unknown : declarations_.unknowns) {
    Coordinate q;
    q.name = unknown.name;
    q.dimension = unknown.dimension;
    q.symbol = symbol(unknown.name, unknown.latex_name);
    q.guess = unknown.guess;
    q.where = unknown.where;
    powers_[q.symbol] = unknown.dimension == Dimension::length ? 1 : 0;
    system_.unknowns.push_back(q);
  }
  // Rates after every coordinate, so a default rate name never takes a coordinate's.
  driver.rate = rate_symbol(input.rate_name, input.name, 1, input.where, "");
  driver.second_rate = rate_symbol(input.second_rate_name, input.name, 2, input.where, "");
  for (std::size_t i = 0; i < system_.unknowns.size(); ++i) {
    const Unknown& unknown = declarations_.unknowns[i];
    system_.unknowns[i].rate = rate_symbol(unknown.rate_name, unknown.name, 1, unknown.where, unknown.latex_name);
    system_.unknowns[i].second_rate =
        rate_symbol(unknown.second_rate_name, unknown.name, 2, unknown.where, unknown.latex_name);
  }
}

std::string PlanarSystemBuilder::unknown_list() const {
  std::string list;
  for (const Unknown& u : declarations_.unknowns) list += (list.empty() ? "" : ", ") + u.name;
  return list;
}

void PlanarSystemBuilder::add_parameters() {
  GiNaC::exmap values;
  std::set<ex, GiNaC::ex_is_less> angles;  // the angle parameters so far
  for (const Parameter& parameter : declarations_.parameters) {
    const std::string context = parameter.where.str() + ": parameter \"" + parameter.name + "\"";
    double value = 0.0;
    std::optional<int> power, plain_power;
    ex formula;
    if (parameter.quantity) {
      value = parameter.quantity->si_value;
      switch (parameter.quantity->dimension) {
        case Dimension::length: power = 1; break;
        case Dimension::angle: power = 0; break;
        case Dimension::number: break;
        default:
          throw UnitError(context + " is " + with_article(dimension_name(parameter.quantity->dimension)) +
                          "; loop parameters are lengths, angles or plain numbers (the driver's "
                          "speed goes under [input] rate)");
      }
    } else {
      // Read before its own symbol exists, so only earlier parameters can be used.
      formula = formulas_.read(parameter.formula, context);
      value = formula_value(formula, values, context, parameter.formula, " (only earlier parameters can be used)");
      power = LengthPower(powers_).of(formula.expand(), context);
      if (misuses_plain_numbers(formula.expand(), false)) check_plain_numbers(formula, context);  // a + k
      plain_power = plain_numbers_.empty() ? power : LengthPower(plain_powers_).of(formula.expand(), context);
    }
    if (!std::isfinite(value)) {
      throw InputError(context + " = \"" + parameter.text + "\" is not a finite number");
    }
    SystemParameter entry;
    entry.symbol = symbol(parameter.name);
    entry.value = value;
    entry.text = parameter.text;
    entry.where = parameter.where;
    if (!parameter.quantity) entry.formula = formula;
    entry.dimension = !power ? Dimension::number : *power == 1 ? Dimension::length
                      : *power == 0 && parameter.quantity && parameter.quantity->dimension == Dimension::angle
                          ? Dimension::angle
                          : Dimension::number;
    if (!parameter.quantity && power == 0 && measures_an_angle(formula, angles)) entry.dimension = Dimension::angle;
    if (entry.dimension == Dimension::angle) angles.insert(entry.symbol);
    if (power) powers_[entry.symbol] = *power;
    if (parameter.quantity) plain_power = power;
    if (parameter.quantity && parameter.quantity->dimension == Dimension::number) {
      plain_power = 0;
      plain_numbers_.push_back({entry.symbol, parameter.name, parameter.text, parameter.where});
    }
    if (plain_power) plain_powers_[entry.symbol] = *plain_power;
    if (!parameter.quantity) formulas_of_parameters_[entry.symbol] = formula;
    values[entry.symbol] = value;
    entry.sets_length_scale = entry.dimension == Dimension::length && parameter.quantity;
    entry.written = !parameter.generated;
    entry.follows = parameter.follows;
    system_.parameters.push_back(entry);
  }
  system_.length_scale = length_scale_of(system_.parameters);
}

}  // namespace kinema
