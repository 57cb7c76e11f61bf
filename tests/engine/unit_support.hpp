// Helpers for the unit tests under tests/loops and tests/engine: models built
// from text in memory (no files, no CLI), symbols looked up by name,
// comparison of expressions by meaning, and the closed-form four-bar that the
// numeric tests check against.
#pragma once

#include <ginac/ginac.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/constraints/constraint_system.hpp"
#include "engine/model.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/symbolic/trig_simplify.hpp"
#include "readers/mechanism_file.hpp"
#include "loops/planar_loops.hpp"

namespace kinema_unit {

constexpr double kDeg = M_PI / 180.0;

/// The constraint system of a mechanism text ("name" stands for its file in messages).
inline kinema::ConstraintSystem system_from_text(const std::string& text, const std::string& name = "unit.toml") {
  return kinema::build_planar_loops(kinema::read_mechanism_text(text, name));
}

/// The whole model (derivation and compiled evaluator) of a mechanism text.
inline kinema::Model model_from_text(const std::string& text, const std::string& name = "unit.toml") {
  return kinema::make_model(kinema::read_mechanism_text(text, name));
}

/// A parameter, coordinate, rate or second rate of the system by its name.
inline GiNaC::ex symbol_named(const kinema::ConstraintSystem& system, const std::string& name) {
  for (const auto& p : system.parameters)
    if (p.symbol.get_name() == name) return p.symbol;
  for (const GiNaC::realsymbol& s : {system.input.symbol, system.input.rate, system.input.second_rate})
    if (s.get_name() == name) return s;
  for (const auto& q : system.unknowns)
    for (const GiNaC::realsymbol& s : {q.symbol, q.rate, q.second_rate})
      if (s.get_name() == name) return s;
  throw std::runtime_error("no symbol named " + name);
}

/// a and b are the same function: a - b, over a common denominator, with products
/// of sines and cosines combined, vanishes.
inline bool same_meaning(const GiNaC::ex& a, const GiNaC::ex& b) {
  const GiNaC::ex difference = GiNaC::normal((a - b).expand());
  return kinema::combine_trig_products(difference.numer().expand()).is_zero();
}

/// A real number from an expression with every symbol substituted.
inline double numeric_value(const GiNaC::ex& e, const GiNaC::exmap& values) {
  const GiNaC::ex v = GiNaC::evalf(e.subs(values));
  if (!GiNaC::is_a<GiNaC::numeric>(v)) throw std::runtime_error("not a number: " + kinema::to_text(v));
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

/// Hand-written closed form of samples/four_bar.toml (a, b, c, d = 40, 120, 80, 100 mm),
/// open branch: B where the circles about A (radius b) and D (radius c) meet, left
/// of the diagonal from A to D.
struct FourBar {
  double a = 0.04, b = 0.12, c = 0.08, d = 0.1;
  double theta3(double theta2) const {
    const double ax = a * std::cos(theta2), ay = a * std::sin(theta2);
    const double diagonal = std::hypot(d - ax, -ay);
    return std::atan2(-ay, d - ax) + std::acos((b * b + diagonal * diagonal - c * c) / (2 * b * diagonal));
  }
  double theta4(double theta2) const {
    const double t3 = theta3(theta2);
    const double bx = a * std::cos(theta2) + b * std::cos(t3), by = a * std::sin(theta2) + b * std::sin(t3);
    return std::atan2(by, bx - d);
  }
  /// Textbook rates for crank rate w2.
  double omega3(double theta2, double w2) const {
    const double t3 = theta3(theta2), t4 = theta4(theta2);
    return a * w2 * std::sin(t4 - theta2) / (b * std::sin(t3 - t4));
  }
  double omega4(double theta2, double w2) const {
    const double t3 = theta3(theta2), t4 = theta4(theta2);
    return a * w2 * std::sin(theta2 - t3) / (c * std::sin(t4 - t3));
  }
};

/// x and y equal as angles (modulo a turn) to within `tolerance` radians.
inline bool same_angle(double x, double y, double tolerance = 1e-9) {
  return std::fabs(std::remainder(x - y, 2 * M_PI)) <= tolerance;
}

}  // namespace kinema_unit
