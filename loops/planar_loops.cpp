#include "loops/planar_loops.hpp"

#include <cctype>
#include <utility>

#include "engine/base/errors.hpp"
#include "engine/constraints/complex_parts.hpp"
#include "loops/planar_system.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

// The loop's terms in the order written, each read on its own; the whole loop when
// the text cannot be split so (the sum of the parts must be the loop).
std::vector<ex> terms_as_written(FormulaReader& formulas, const std::string& formula, const ex& loop,
                                 const std::string& context) {
  std::vector<ex> terms;
  ex sum = 0;
  try {
    for (const std::string& text : formula.empty() ? std::vector<std::string>{} : written_terms(formula)) {
      terms.push_back(formulas.read(text, context));
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

}  // namespace

ConstraintSystem build_planar_loops(const Mechanism& mechanism) {
  PlanarSystemBuilder builder(mechanism);
  FormulaReader& formulas = builder.formulas();
  for (const Loop& loop : mechanism.loops) {
    const std::string context = loop.where.str() + ": loop \"" + loop.name + "\"";
    PlanarVector written{loop.name, loop.where, 0, {}, loop.complex_formula, false};
    if (!loop.complex_formula.empty()) {
      written.vector = formulas.read(loop.complex_formula, context);
      written.terms = terms_as_written(formulas, loop.complex_formula, written.vector, context);
      builder.add_loop(written);
    } else {
      const ex x = formulas.read(loop.x_formula, context + " (x)");
      const ex y = formulas.read(loop.y_formula, context + " (y)");
      if (!imag_part_of(x).is_zero() || !imag_part_of(y).is_zero()) {
        throw InputError(context + ": x and y components must be real (no I)");
      }
      written.vector = x + GiNaC::I * y;
      written.terms = terms_as_written(formulas, "", written.vector, context);
      builder.add_loop(written, x, y);
    }
  }
  builder.end_loops();
  for (const Point& point : mechanism.points) {
    const std::string context = point.where.str() + ": point \"" + point.name + "\"";
    PlanarVector written{point.name, point.where, formulas.read(point.formula, context), {}, point.formula, point.is_joint};
    written.terms = terms_as_written(formulas, point.formula, written.vector, context);
    builder.add_point(written);
  }
  return std::move(builder).system();
}

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
