#include <kinema/loops/planar_loops.hpp>

#include <cmath>
#include <map>
#include <optional>
#include <sstream>

#include <kinema/engine/errors.hpp>
#include <kinema/engine/symbolic/expression_parts.hpp>

namespace kinema {
namespace {

using GiNaC::ex;

/// Length exponent of a formula ("a*exp(I*theta)" -> 1, "theta" -> 0);
/// nullopt where it cannot be known (plain-number parameters, bare constants).
class LengthPower {
 public:
  explicit LengthPower(std::map<ex, int, GiNaC::ex_is_less> powers) : powers_(std::move(powers)) {}

  /// Throws InputError(context + why) on a mismatch.
  std::optional<int> of(const ex& e, const std::string& context) const {
    if (GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::constant>(e)) return std::nullopt;
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      auto found = powers_.find(e);
      if (found == powers_.end()) return std::nullopt;
      return found->second;
    }
    if (GiNaC::is_a<GiNaC::add>(e)) {
      std::optional<int> common;
      ex first;
      for (const ex& term : e) {
        auto power = of(term, context);
        if (!power) continue;
        if (common && *common != *power) {
          throw InputError(context + ": the terms \"" + to_text(first) + "\" and \"" +
                           to_text(term) + "\" have different units (" + describe(*common) +
                           " and " + describe(*power) + "); check the units of the parameters");
        }
        common = power;
        first = term;
      }
      return common;
    }
    if (GiNaC::is_a<GiNaC::mul>(e)) {
      int total = 0;
      for (const ex& factor : e) {
        if (GiNaC::is_a<GiNaC::numeric>(factor)) continue;
        auto power = of(factor, context);
        if (!power) return std::nullopt;
        total += *power;
      }
      return total;
    }
    if (GiNaC::is_a<GiNaC::power>(e)) {
      auto base = of(e.op(0), context);
      if (!base) return std::nullopt;
      const ex exponent = e.op(1);
      if (*base == 0) return 0;
      if (GiNaC::is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_integer()) {
        return *base * GiNaC::ex_to<GiNaC::numeric>(exponent).to_int();
      }
      if (exponent.is_equal(GiNaC::numeric(1, 2)) && *base % 2 == 0) return *base / 2;
      return std::nullopt;
    }
    if (GiNaC::is_a<GiNaC::function>(e)) {
      const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
      if (name == "abs") return of(e.op(0), context);
      if (name == "atan2") {
        auto y = of(e.op(0), context), x = of(e.op(1), context);
        if (y && x && *y != *x) {
          throw InputError(context + ": atan2 needs two arguments of the same unit in \"" + to_text(e) + "\"");
        }
        return 0;
      }
      for (const ex& argument : e) {
        auto power = of(argument, context);
        if (power && *power != 0) {
          throw InputError(context + ": the argument of " + name + "(...) in \"" + to_text(e) +
                           "\" is a " + describe(*power) + ", but an angle or a plain number "
                           "is needed there");
        }
      }
      return 0;
    }
    return std::nullopt;
  }

  static std::string describe(int power) {
    if (power == 0) return "angle or plain number";
    if (power == 1) return "length";
    return "length^" + std::to_string(power);
  }

 private:
  std::map<ex, int, GiNaC::ex_is_less> powers_;
};

class Builder {
 public:
  explicit Builder(const Mechanism& mechanism) : mechanism_(mechanism) {}

  LoopClosure build() {
    LoopClosure closure;
    add_parameters(closure);
    closure.input = symbol(mechanism_.input.name);
    powers_[closure.input] = mechanism_.input.dimension == Dimension::length ? 1 : 0;
    for (const Unknown& unknown : mechanism_.unknowns) {
      closure.unknowns.push_back(symbol(unknown.name));
      powers_[closure.unknowns.back()] = unknown.dimension == Dimension::length ? 1 : 0;
    }
    const LengthPower units(powers_);

    for (std::size_t k = 0; k < mechanism_.loops.size(); ++k) {
      const Loop& loop = mechanism_.loops[k];
      const std::string context = loop.where.str() + ": loop \"" + loop.name + "\"";
      ex x, y, vector;
      if (!loop.complex_formula.empty()) {
        vector = parse(loop.complex_formula, context);
        x = vector.real_part().expand();
        y = vector.imag_part().expand();
      } else {
        x = parse(loop.x_formula, context + " (x)");
        y = parse(loop.y_formula, context + " (y)");
        if (has_imaginary(x) || has_imaginary(y)) {
          throw InputError(context + ": x and y components must be real (no I)");
        }
        vector = x + GiNaC::I * y;
      }
      auto power = units.of(vector.expand(), context);
      if (power && *power != 1) {
        throw InputError(context + " is a " + LengthPower::describe(*power) +
                         ", but a loop is a sum of link vectors (lengths)");
      }
      if (!depends_on_unknowns(x, closure) && !depends_on_unknowns(y, closure)) {
        throw InputError(context + " contains none of the unknowns; each loop must close "
                         "through at least one unknown coordinate");
      }
      closure.loop_vectors.push_back(vector);
      closure.equations.push_back(x);
      closure.equations.push_back(y);
      closure.equation_loop.push_back(k);
      closure.equation_loop.push_back(k);
    }
    const std::size_t equations = closure.equations.size();
    const std::size_t unknowns = closure.unknowns.size();
    if (equations != unknowns) {
      throw InputError(mechanism_.source_file + ": " + std::to_string(mechanism_.loops.size()) +
                       " loop(s) give " + std::to_string(equations) + " scalar equations, but there are " +
                       std::to_string(unknowns) + " unknowns (" + unknown_list() +
                       "); each vector loop closes two unknowns: add or remove a loop or an unknown");
    }
    for (std::size_t i = 0; i < unknowns; ++i) {
      bool used = false;
      for (const ex& equation : closure.equations) used = used || equation.has(closure.unknowns[i]);
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
        throw InputError(context + " is a " + LengthPower::describe(*power) +
                         ", but a point position must be a length (x + I*y)");
      }
      closure.point_positions.push_back(position);
      closure.point_x.push_back(position.real_part().expand());
      closure.point_y.push_back(position.imag_part().expand());
    }
    return closure;
  }

 private:
  const Mechanism& mechanism_;
  GiNaC::symtab table_;
  std::map<ex, int, GiNaC::ex_is_less> powers_;

  GiNaC::realsymbol symbol(const std::string& name) {
    GiNaC::realsymbol s(name);
    table_[name] = s;
    return s;
  }

  std::string unknown_list() const {
    std::string list;
    for (const Unknown& u : mechanism_.unknowns) list += (list.empty() ? "" : ", ") + u.name;
    return list;
  }

  static bool has_imaginary(const ex& e) { return !e.imag_part().expand().is_zero(); }

  static bool depends_on_unknowns(const ex& e, const LoopClosure& closure) {
    for (const auto& q : closure.unknowns)
      if (e.has(q)) return true;
    return false;
  }

  ex parse(const std::string& formula, const std::string& context) {
    GiNaC::parser reader(table_, /*strict=*/true);
    try {
      return reader(formula);
    } catch (const std::exception& error) {
      std::string why = error.what();
      const std::string marker = "symbol \"";
      const auto at = why.find(marker);
      if (at != std::string::npos) {
        const auto end = why.find('"', at + marker.size());
        const std::string name = why.substr(at + marker.size(), end - at - marker.size());
        throw InputError(context + ": unknown name \"" + name + "\" in \"" + formula +
                         "\"; define it under [parameters] or [unknowns], or check the spelling");
      }
      const auto newline = why.find('\n');
      if (newline != std::string::npos) why = why.substr(0, newline);
      throw InputError(context + ": cannot read the formula \"" + formula + "\" (" + why + ")");
    }
  }

  void add_parameters(LoopClosure& closure) {
    GiNaC::exmap values;
    for (const Parameter& parameter : mechanism_.parameters) {
      const std::string context = parameter.where.str() + ": parameter \"" + parameter.name + "\"";
      double value = 0.0;
      std::optional<int> power;
      ex formula;
      if (parameter.quantity) {
        value = parameter.quantity->si_value;
        switch (parameter.quantity->dimension) {
          case Dimension::length: power = 1; break;
          case Dimension::angle: power = 0; break;
          case Dimension::number: break;
          default:
            throw UnitError(context + " is a " + dimension_name(parameter.quantity->dimension) +
                            "; loop parameters are lengths, angles or plain numbers (the driver's "
                            "speed goes under [input] rate)");
        }
      } else {
        // Parsed before its own symbol exists, so only earlier parameters can be used.
        formula = parse(parameter.formula, context);
        const ex numeric = GiNaC::evalf(formula.subs(values));
        if (!GiNaC::is_a<GiNaC::numeric>(numeric) || !GiNaC::ex_to<GiNaC::numeric>(numeric).is_real()) {
          throw InputError(context + " = \"" + parameter.formula + "\" does not evaluate to a real "
                           "number (only earlier parameters can be used)");
        }
        value = GiNaC::ex_to<GiNaC::numeric>(numeric).to_double();
        power = LengthPower(powers_).of(formula.expand(), context);
      }
      if (!std::isfinite(value)) {
        throw InputError(context + " = \"" + parameter.text + "\" is not a finite number");
      }
      GiNaC::realsymbol s = symbol(parameter.name);
      if (!parameter.quantity) closure.parameter_formulas[s] = formula;
      if (power) powers_[s] = *power;
      values[s] = value;
      closure.parameters.push_back(s);
      closure.parameter_values.push_back(value);
    }
  }
};

}  // namespace

LoopClosure build_loop_closure(const Mechanism& mechanism) { return Builder(mechanism).build(); }

GiNaC::ex expand_parameter_formulas(const LoopClosure& closure, const GiNaC::ex& e) {
  ex result = e;
  // Formulas refer only to earlier parameters, so a few passes reach quantities.
  for (std::size_t pass = 0; pass <= closure.parameter_formulas.size(); ++pass) {
    ex next = result.subs(closure.parameter_formulas);
    if (next.is_equal(result)) break;
    result = next;
  }
  return result;
}

}  // namespace kinema
