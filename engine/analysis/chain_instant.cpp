#include "engine/analysis/chain_instant.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "engine/base/work_count.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/symbolic/trig_simplify.hpp"
#include "engine/base/units.hpp"

namespace kinema {

using GiNaC::ex;

bool is_driven_chain(const ConstraintSystem& system) {
  if (system.frames.empty()) return false;
  return std::all_of(system.groups.begin(), system.groups.end(),
                     [](const EquationGroup& group) { return group.kind == "motion"; });
}

bool is_negative_term(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) return GiNaC::ex_to<GiNaC::numeric>(e).is_negative();
  if (!GiNaC::is_a<GiNaC::mul>(e)) return false;
  const ex last = e.op(e.nops() - 1);  // GiNaC keeps a product's number last
  return GiNaC::is_a<GiNaC::numeric>(last) && GiNaC::ex_to<GiNaC::numeric>(last).is_negative();
}

std::string chain_observer(const ConstraintSystem& system) {
  for (const FrameObservable& f : system.frames) {
    const bool is_frame = std::any_of(system.frames.begin(), system.frames.end(),
                                      [&](const FrameObservable& g) { return g.name == f.parent; });
    if (!is_frame) return f.parent;
  }
  return "";
}

namespace {

// An angle that is a rational number of degrees (30 deg, -20 deg, 12.5 deg: what a file
// writes) as that multiple of Pi, so that sin and cos of it are exact where GiNaC knows
// them (sin(Pi/6) = 1/2); anything else as the float it is.
ex exact_angle(double radians) {
  if (radians == 0) return 0;
  const double degrees = radians * 180 / kPi;
  for (long denominator = 1; denominator <= 1000; ++denominator) {
    const double scaled = degrees * double(denominator);
    if (std::fabs(scaled) > 1e12) break;
    if (std::fabs(scaled - std::round(scaled)) < 1e-9 * double(denominator))
      return GiNaC::Pi * GiNaC::numeric(std::lround(scaled), 180 * denominator);
  }
  return radians;
}

bool has_symbol(const ex& e) {
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) return true;
  return false;
}
bool has_float(const ex& e) {
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::numeric>(*it) && !GiNaC::ex_to<GiNaC::numeric>(*it).is_rational()) return true;
  return false;
}

// sin and cos of an angle GiNaC leaves as it is (sin(Pi/9)) as floats: kept exact they
// would not cancel (sin^2 + cos^2 stays), and the formula should read as numbers.
struct FloatTrig : GiNaC::map_function {
  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::function>(e) && !has_symbol(e)) return GiNaC::evalf(e);
    return e.map(*this);
  }
};

// A term's number (its factors without symbols, as a float when any is) and the rest.
std::pair<ex, ex> split_term(const ex& term) {
  ex number = 1, rest = 1;
  if (GiNaC::is_a<GiNaC::mul>(term)) {
    for (const ex& f : term) (has_symbol(f) ? rest : number) *= f;
  } else {
    (has_symbol(term) ? rest : number) *= term;
  }
  if (has_float(number)) number = GiNaC::evalf(number);
  return {number, rest};
}

double magnitude(const ex& number) {
  const ex v = GiNaC::evalf(number);
  return GiNaC::is_a<GiNaC::numeric>(v) ? std::fabs(GiNaC::ex_to<GiNaC::numeric>(v).to_double()) : 0.0;
}

// The largest number of a term in e (a sum or one term).
double largest_number(const ex& e) {
  double largest = 0;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    for (const ex& t : e) largest = std::max(largest, magnitude(split_term(t).first));
  } else if (!e.is_zero()) {
    largest = magnitude(split_term(e).first);
  }
  return largest;
}

// Each term with its number as one float where it has a float in it (0.17101*sqrt(3)
// reads as 0.296198), and without the terms whose float number is round-off: zero at the
// scale of the vector's largest (zero_at_scale) (sin(Pi/9)^2 + cos(Pi/9)^2 - 1 in floats is 2.7e-20, not a term).
// Sums inside products too: combining sin and cos products (cos(2*alpha)*(... +
// 2.7e-20*L3*alpha5)) adds floats that cancel.
struct TidyTerms : GiNaC::map_function {
  double scale;
  explicit TidyTerms(double s) : scale(s) {}
  ex tidy(const ex& term) const {
    const auto [number, rest] = split_term(term);
    if (has_float(number) && zero_at_scale(magnitude(number), scale) == 0) return 0;
    return number * rest;
  }
  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::symbol>(e) || GiNaC::is_a<GiNaC::constant>(e)) return e;
    const ex inner = e.map(*this);
    if (!GiNaC::is_a<GiNaC::add>(inner)) return inner;
    ex sum = 0;
    for (const ex& t : inner) sum += tidy(t);
    return sum;
  }
};
ex tidy_terms(const ex& e, double scale) {
  TidyTerms tidy(scale);
  const ex inner = tidy(e);
  return GiNaC::is_a<GiNaC::add>(inner) ? inner : tidy.tidy(inner);
}

// The floats of e to `digits` significant digits: what a printer that shows a float's
// shortest form prints (TextbookForm::set_exact_floats), so the formula as printed is the
// formula whose number is checked.
struct RoundFloats : GiNaC::map_function {
  int digits;
  explicit RoundFloats(int d) : digits(d) {}
  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::numeric>(e)) {
      const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
      if (n.is_rational() || !n.is_real()) return e;
      char text[64];
      std::snprintf(text, sizeof text, "%.*g", digits, n.to_double());
      return GiNaC::numeric(std::strtod(text, nullptr));
    }
    return e.map(*this);
  }
};

// The symbols at the instant: joint variables (as exact as they are: 0 stays 0, so
// that sin and cos of it simplify) and constant angles of a quarter turn (beta = 90 deg
// is put in, as seed 000 does: sin and cos of it are 0 and 1); for the numbers every
// parameter and rate too.
struct Instant {
  GiNaC::exmap angles, numbers;
  std::vector<std::pair<Coordinate, double>> values;
  std::string where;  // the instant, for a message: "t = 0 s", "theta1 = 30 deg"
  std::string source_file;

  explicit Instant(const ConstraintSystem& system) : source_file(system.source_file) {
    for (const SystemParameter& p : system.parameters) {
      numbers[p.symbol] = p.value;
      const double quarters = p.value / (kPi / 2);
      if (p.dimension == Dimension::angle && !p.formula && std::fabs(quarters - std::round(quarters)) < 1e-12)
        angles[p.symbol] = GiNaC::numeric(static_cast<long>(std::round(quarters))) * GiNaC::Pi / 2;
    }
    const auto parameter_value = [&](const std::string& name) {
      for (const SystemParameter& p : system.parameters)
        if (p.symbol.get_name() == name) return p.value;
      return 0.0;
    };
    const auto put = [&](const Coordinate& q, double value, double rate, double second_rate) {
      angles[q.symbol] = q.dimension == Dimension::angle ? exact_angle(value) : value == 0 ? ex(0) : ex(value);
      numbers[q.symbol] = value;
      numbers[q.rate] = rate;
      numbers[q.second_rate] = second_rate;
      values.push_back({q, value});
    };
    const Driver& input = system.input;
    if (input.dimension != Dimension::time) {
      put(input, input.values.front(), input.rate_value, input.second_rate_value);
      const OutputScale scale(system);
      where = input.symbol.get_name() + " = " + format_significant(scale.input(input.values.front())) + " " +
              scale.coordinate_unit(input.dimension);
    } else {  // formulas of time at the instant t = 0
      angles[input.symbol] = 0;
      numbers[input.symbol] = 0;
      where = input.symbol.get_name() + " = 0 s";
    }
    for (const Coordinate& q : system.unknowns) {
      put(q, q.guess, parameter_value(q.rate.get_name() + "_0"), parameter_value(q.second_rate.get_name() + "_0"));
    }
  }

  // GiNaC refuses a formula that divides by zero at the instant (abs(t)' = abs(t)/t,
  // sqrt(t)' at t = 0): the rates are not defined there, as at a singular position.
  [[noreturn]] void undefined(const std::domain_error& error) const {
    throw SingularPositionError(source_file + ": the chain's rates are not defined at " + where +
                                ", the instant derive and latex work out (" + error.what() +
                                "); a motion written with abs(), sqrt() or a division by the input is not "
                                "differentiable there: eval gives the rates at other values");
  }

  // The components at the instant: expanded, exact angles put in, round-off dropped.
  std::vector<ex> plain(const std::vector<ex>& v) const try {
    std::vector<ex> result;
    FloatTrig floats;
    double scale = 0;
    for (const ex& c : v) {
      result.push_back(floats(c.subs(angles, GiNaC::subs_options::no_pattern)).expand());
      scale = std::max(scale, largest_number(result.back()));
    }
    for (ex& c : result) c = tidy_terms(c, scale);
    return result;
  } catch (const std::domain_error& error) {
    undefined(error);
  }

  // The shorter of the expanded formula and the one with products of sin/cos combined,
  // its floats to as few digits (6 at least) as give `value` again to 1e-8 (the printed
  // numbers have 6): the formula as printed reproduces the printed number.
  ex formula(const ex& plain, double scale, double value) const try {
    ex combined = tidy_terms(combine_trig_products(plain), scale);
    const ex shorter = to_text(combined).size() < to_text(plain).size() ? combined : plain;
    if (!has_float(shorter)) return shorter;
    for (int digits = 6; digits < 17; ++digits) {
      RoundFloats round(digits);
      const ex rounded = round(shorter);
      if (std::fabs(number(rounded) - value) <= 1e-8 * std::fabs(value) + 1e-14) return rounded;
    }
    RoundFloats round(17);
    return round(shorter);
  } catch (const std::domain_error& error) {
    undefined(error);
  }

  double number(const ex& e) const try {
    const ex value = GiNaC::evalf(e.subs(numbers, GiNaC::subs_options::no_pattern));
    double x = GiNaC::is_a<GiNaC::numeric>(value) ? GiNaC::ex_to<GiNaC::numeric>(value).to_double() : NAN;
    return zero_at_scale(x, 1);  // rounding of an exact zero (SI: at the scale of a unit; views again at theirs)
  } catch (const std::domain_error& error) {
    undefined(error);
  }
};

}  // namespace

// The rotation of frame `basis` (its axes as columns), empty for the observer's basis;
// InputError naming the frames for a basis that is not one of them.
static std::vector<ex> basis_rotation(const ConstraintSystem& system, const std::string& basis) {
  const std::string observer = chain_observer(system);
  if (basis.empty() || basis == observer) return {};
  std::string names = observer;
  std::vector<ex> rotation;
  for (const FrameObservable& f : system.frames) {
    names += ", " + f.name;
    if (f.name == basis) rotation = f.rotation;
  }
  if (rotation.empty()) {
    throw InputError(system.source_file + ": --basis " + basis + ": there is no frame \"" + basis +
                     "\" in the chain; the frames are " + names);
  }
  return rotation;
}

void check_chain_basis(const ConstraintSystem& system, const std::string& basis) { basis_rotation(system, basis); }

ChainAtInstant chain_at_instant(const ConstraintSystem& system, const std::string& basis) {
  count_work(Work::chain_at_instant);
  ChainAtInstant chain;
  chain.observer = chain_observer(system);
  chain.basis = basis.empty() ? chain.observer : basis;
  // Components along the basis frame's axes: R^T v (R's columns are its axes).
  const std::vector<ex> rotation = basis_rotation(system, basis);
  const Instant at(system);
  chain.values = at.values;

  const auto vector = [&](ChainTerm term, const std::vector<ex>& v) {
    ChainVector result{term, {}, {}};
    std::vector<ex> components;
    for (std::size_t c = 0; c < 3; ++c) {
      ex component = v[c];
      if (!rotation.empty()) component = rotation[0 * 3 + c] * v[0] + rotation[1 * 3 + c] * v[1] + rotation[2 * 3 + c] * v[2];
      components.push_back(component);
      result.value[c] = at.number(component);
    }
    const std::vector<ex> plain = at.plain(components);
    double scale = 0;
    for (const ex& c : plain) scale = std::max(scale, largest_number(c));
    for (std::size_t c = 0; c < 3; ++c) result.formula.push_back(at.formula(plain[c], scale, result.value[c]));
    return result;
  };
  const auto sum = [](std::initializer_list<const std::vector<ex>*> parts) {
    std::vector<ex> total(3, 0);
    for (const auto* part : parts)
      for (std::size_t c = 0; c < 3; ++c) total[c] += (*part)[c];
    return total;
  };

  for (const FrameObservable& f : system.frames) {
    ChainFrameAtInstant frame{f.name, f.parent, f.angular_velocity_terms,
                              vector(ChainTerm::angular_velocity, f.angular_velocity),
                              vector(ChainTerm::angular_acceleration, f.angular_acceleration), {}};
    for (const AngularVelocityTerm& t : f.angular_velocity_terms)
      frame.acceleration_parts.push_back({vector(ChainTerm::rate_change, t.rate_change), vector(ChainTerm::carried, t.carried)});
    chain.frames.push_back(frame);
  }
  for (const PointObservable& p : system.points) {
    if (!p.terms) continue;
    const RelativeMotionTerms& t = *p.terms;
    ChainPointAtInstant point{p.name, t.frame, {}, {}};
    point.velocity = {vector(ChainTerm::position, t.relative_position),
                      vector(ChainTerm::frame_velocity, t.frame_velocity), vector(ChainTerm::transport, t.transport),
                      vector(ChainTerm::relative_velocity, t.relative_velocity),
                      vector(ChainTerm::velocity, sum({&t.frame_velocity, &t.transport, &t.relative_velocity}))};
    point.acceleration = {
        vector(ChainTerm::frame_acceleration, t.frame_acceleration), vector(ChainTerm::tangential, t.tangential),
        vector(ChainTerm::centripetal, t.centripetal), vector(ChainTerm::coriolis, t.coriolis),
        vector(ChainTerm::relative_acceleration, t.relative_acceleration),
        vector(ChainTerm::acceleration, sum({&t.frame_acceleration, &t.tangential, &t.centripetal, &t.coriolis,
                                             &t.relative_acceleration}))};
    chain.points.push_back(point);
  }
  return chain;
}

}  // namespace kinema
