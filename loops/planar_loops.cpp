#include "loops/planar_loops.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "engine/base/errors.hpp"
#include "engine/constraints/complex_parts.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/base/naming.hpp"
#include "engine/constraints/formula_reader.hpp"
#include "engine/constraints/length_power.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

class Builder {
 public:
  explicit Builder(const Mechanism& mechanism) : mechanism_(mechanism) {}

  ConstraintSystem build() {
    // Before the loops are read: their checks grow with the square of the count.
    check_unknown_count(mechanism_.unknowns);
    ConstraintSystem system;
    system.title = mechanism_.title;
    system.description = mechanism_.description;
    system.source_file = mechanism_.source_file;
    system.output = mechanism_.output;
    add_parameters(system);
    add_coordinates(system);
    const LengthPower units(powers_);

    for (std::size_t k = 0; k < mechanism_.loops.size(); ++k) {
      const Loop& loop = mechanism_.loops[k];
      const std::string context = loop.where.str() + ": loop \"" + loop.name + "\"";
      ex x, y, vector;
      EquationGroup group;
      group.kind = "loop";
      group.name = loop.name;
      group.where = loop.where;
      if (!loop.complex_formula.empty()) {
        vector = parse(loop.complex_formula, context);
        x = real_part_of(vector);
        y = imag_part_of(vector);
        check_separated(x, y, loop.complex_formula, context);
        group.terms = terms_as_written(loop.complex_formula, vector, context);
      } else {
        x = parse(loop.x_formula, context + " (x)");
        y = parse(loop.y_formula, context + " (y)");
        if (has_imaginary(x) || has_imaginary(y)) {
          throw InputError(context + ": x and y components must be real (no I)");
        }
        vector = x + GiNaC::I * y;
        group.terms = terms_as_written("", vector, context);
      }
      auto power = units.of(vector.expand(), context);
      if (power && *power != 1) {
        throw InputError(context + " is " + with_article(LengthPower::describe(*power)) +
                         ", but a loop is a sum of link vectors (lengths)");
      }
      if (misuses_plain_numbers(vector.expand(), true)) check_plain_numbers(vector, context);
      if (!depends_on_unknowns(x, system) && !depends_on_unknowns(y, system)) {
        throw InputError(context + " contains none of the unknowns; each loop must close "
                         "through at least one unknown coordinate");
      }
      group.vector = vector;
      // The two rows of a planar loop: the only place that knows a loop is two equations.
      for (const auto& [component, expression] : {std::make_pair("x", x), std::make_pair("y", y)}) {
        group.equations.push_back(system.equations.size());
        system.equations.push_back({expression, k, component});
      }
      system.groups.push_back(group);
    }
    const std::size_t equations = system.equations.size();
    const std::size_t unknowns = system.unknowns.size();
    if (equations != unknowns) {
      // Where the count is passed: the first unknown without an equation, or the first
      // loop without unknowns.
      const SourceLocation where = unknowns > equations ? mechanism_.unknowns[equations].where
                                                        : mechanism_.loops[unknowns / 2].where;
      throw InputError(where.str() + ": " + std::to_string(mechanism_.loops.size()) +
                       " loop(s) give " + std::to_string(equations) + " scalar equations, but there are " +
                       std::to_string(unknowns) + " unknowns (" + unknown_list() +
                       "); each vector loop closes two unknowns: add or remove a loop or an unknown");
    }
    for (std::size_t i = 0; i < unknowns; ++i) {
      bool used = false;
      for (const Equation& equation : system.equations) used = used || equation.expression.has(system.unknowns[i].symbol);
      if (!used) {
        throw InputError(mechanism_.unknowns[i].where.str() + ": unknown \"" +
                         mechanism_.unknowns[i].name + "\" appears in no loop");
      }
    }

    for (const Point& point : mechanism_.points) {
      const std::string context = point.where.str() + ": point \"" + point.name + "\"";
      ex position = parse(point.formula, context);
      auto power = units.of(position.expand(), context);
      if (power && *power != 1) {
        throw InputError(context + " is " + with_article(LengthPower::describe(*power)) +
                         ", but a point position must be a length (x + I*y)");
      }
      if (misuses_plain_numbers(position.expand(), true)) check_plain_numbers(position, context);
      PointObservable observable;
      observable.name = point.name;
      observable.where = point.where;
      observable.is_joint = point.is_joint;
      observable.components = {"x", "y"};
      observable.position = {real_part_of(position), imag_part_of(position)};
      check_separated(observable.position[0], observable.position[1], point.formula, context);
      observable.written = position;
      observable.written_terms = terms_as_written(point.formula, position, context);
      system.points.push_back(observable);
    }
    return system;
  }

 private:
  const Mechanism& mechanism_;
  // One reader for every formula: its symbol table grows as names are defined
  // (a parser per formula copied the table each time: quadratic in the parameters).
  FormulaReader formulas_;
  std::map<ex, int, GiNaC::ex_is_less> powers_;
  // A parameter written as a bare number ("40") is a plain number (a ratio: p = "k*a"),
  // not metres: powers_ leaves it out (a formula with it may be anything), plain_powers_
  // counts it as of no length. A formula that is a length with the one and not with the
  // other uses such a number as a length.
  struct PlainNumber {
    GiNaC::realsymbol symbol;
    std::string name, text;
    SourceLocation where;
  };
  std::vector<PlainNumber> plain_numbers_;
  LengthPower::Powers plain_powers_;
  GiNaC::exmap formulas_of_parameters_;

  // Whether `e` (a length, or with length false anything) stops being one, or mixes
  // units, once bare numbers count as of no length.
  bool misuses_plain_numbers(const ex& e, bool length) const {
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
  void check_plain_numbers(const ex& e, const std::string& used_in) const {
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
  std::set<std::string> taken_;  ///< Names of symbols so far (rate names must not clash).

  GiNaC::realsymbol symbol(const std::string& name, const std::string& latex = "") {
    GiNaC::realsymbol s(name, latex.empty() ? latex_symbol_name(name) : latex);
    formulas_.define(name, s);
    taken_.insert(name);
    return s;
  }

  // The file's rate name, else the textbook's (omega3, alpha3), else name_dot on a clash.
  GiNaC::realsymbol rate_symbol(const std::string& given, const std::string& coordinate, int order,
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

  void add_coordinates(ConstraintSystem& system) {
    const Input& input = mechanism_.input;
    Driver& driver = system.input;
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
    for (const Unknown& unknown : mechanism_.unknowns) {
      Coordinate q;
      q.name = unknown.name;
      q.dimension = unknown.dimension;
      q.symbol = symbol(unknown.name, unknown.latex_name);
      q.guess = unknown.guess;
      q.where = unknown.where;
      powers_[q.symbol] = unknown.dimension == Dimension::length ? 1 : 0;
      system.unknowns.push_back(q);
    }
    // Rates after every coordinate, so a default rate name never takes a coordinate's.
    driver.rate = rate_symbol(input.rate_name, input.name, 1, input.where, "");
    driver.second_rate = rate_symbol(input.second_rate_name, input.name, 2, input.where, "");
    for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
      const Unknown& unknown = mechanism_.unknowns[i];
      system.unknowns[i].rate = rate_symbol(unknown.rate_name, unknown.name, 1, unknown.where, unknown.latex_name);
      system.unknowns[i].second_rate =
          rate_symbol(unknown.second_rate_name, unknown.name, 2, unknown.where, unknown.latex_name);
    }
  }

  std::string unknown_list() const {
    std::string list;
    for (const Unknown& u : mechanism_.unknowns) list += (list.empty() ? "" : ", ") + u.name;
    return list;
  }

  static bool has_imaginary(const ex& e) { return !imag_part_of(e).is_zero(); }

  // The x and y parts must be real functions the evaluator compiles: a function of a
  // complex argument other than exp(I*...) (log(I*phi4) has the part log(abs(I*phi4)))
  // does not separate so, and is refused here rather than failing in the compiler.
  static void check_separated(const ex& x, const ex& y, const std::string& formula, const std::string& context) {
    for (const ex& part : {x, y}) {
      bool separated = !part.has(GiNaC::I);
      for (auto it = part.preorder_begin(); separated && it != part.preorder_end(); ++it)
        separated = !GiNaC::is_a<GiNaC::function>(*it) || is_compiled_function(GiNaC::ex_to<GiNaC::function>(*it).get_name());
      if (!separated) {
        throw InputError(context + ": \"" + formula + "\" cannot be split into real x and y parts: only exp(I*angle) "
                         "may take a complex argument (not log(I*phi), say); write it by components, "
                         "{ x = \"...\", y = \"...\" }");
      }
    }
  }

  static bool depends_on_unknowns(const ex& e, const ConstraintSystem& system) {
    for (const auto& q : system.unknowns)
      if (e.has(q.symbol)) return true;
    return false;
  }

  // The loop's terms in the order written, each parsed on its own; the whole loop
  // when the text cannot be split so (the sum of the parts must be the loop).
  std::vector<ex> terms_as_written(const std::string& formula, const ex& loop, const std::string& context) {
    std::vector<ex> terms;
    ex sum = 0;
    try {
      for (const std::string& text : formula.empty() ? std::vector<std::string>{} : written_terms(formula)) {
        terms.push_back(formulas_.read(text, context));
        sum += terms.back();
      }
    } catch (const std::exception&) {
      terms.clear();
    }
    if (terms.empty() || !(sum - loop).expand().is_zero()) {
      const ex expanded = loop.expand();
      terms.clear();
      if (GiNaC::is_a<GiNaC::add>(expanded)) {
        for (const ex& term : expanded) terms.push_back(term);
      } else {
        terms.push_back(expanded);
      }
    }
    return terms;
  }

  ex parse(const std::string& formula, const std::string& context) { return formulas_.read(formula, context); }

  void add_parameters(ConstraintSystem& system) {
    GiNaC::exmap values;
    double largest = 0;
    for (const Parameter& parameter : mechanism_.parameters) {
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
        // Parsed before its own symbol exists, so only earlier parameters can be used.
        formula = parse(parameter.formula, context);
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
      if (power) powers_[entry.symbol] = *power;
      if (parameter.quantity) plain_power = power;
      if (parameter.quantity && parameter.quantity->dimension == Dimension::number) {
        plain_power = 0;
        plain_numbers_.push_back({entry.symbol, parameter.name, parameter.text, parameter.where});
      }
      if (plain_power) plain_powers_[entry.symbol] = *plain_power;
      if (!parameter.quantity) formulas_of_parameters_[entry.symbol] = formula;
      values[entry.symbol] = value;
      if (entry.dimension == Dimension::length && parameter.quantity) largest = std::max(largest, std::fabs(value));
      system.parameters.push_back(entry);
    }
    system.length_scale = largest > 0 ? largest : 1.0;
  }
};

}  // namespace

ConstraintSystem build_planar_loops(const Mechanism& mechanism) { return Builder(mechanism).build(); }

// Top-level terms of a formula as written ("a*exp(I*t) - d" -> "a*exp(I*t)", "-d"),
// so the drawing follows the chain in the order the user wrote the loop.
std::vector<std::string> written_terms(const std::string& formula) {
  std::vector<std::string> terms;
  std::string current;
  int depth = 0;
  for (std::size_t i = 0; i < formula.size(); ++i) {
    const char c = formula[i];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    const bool sign = (c == '+' || c == '-') && depth == 0;
    // Not a sign of an exponent (1e-3) and not the first character.
    const bool exponent = i > 0 && (formula[i - 1] == 'e' || formula[i - 1] == 'E') && i > 1 &&
                          std::isdigit(static_cast<unsigned char>(formula[i - 2]));
    if (sign && !exponent && current.find_first_not_of(" \t") != std::string::npos) {
      terms.push_back(current);
      current.clear();
    }
    current += c;
  }
  if (current.find_first_not_of(" \t") != std::string::npos) terms.push_back(current);
  return terms;
}



}  // namespace kinema
