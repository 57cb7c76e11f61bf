#include "engine/constraints/length_power.hpp"

#include "engine/base/errors.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/base/units.hpp"

namespace kinema {

using GiNaC::ex;

std::optional<int> LengthPower::of(const ex& e, const std::string& context) const {
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
                         "\" is " + with_article(describe(*power)) + ", but an angle or a plain number "
                         "is needed there");
      }
    }
    return 0;
  }
  return std::nullopt;
}

std::string LengthPower::describe(int power) {
  if (power == 0) return "angle or plain number";
  if (power == 1) return "length";
  return "length^" + std::to_string(power);
}

namespace {

// A number written as such: 2, Pi, Pi/2.
bool is_a_number(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::constant>(e)) return true;
  if (!GiNaC::is_a<GiNaC::mul>(e)) return false;
  for (const ex& factor : e)
    if (!is_a_number(factor)) return false;
  return true;
}

}  // namespace

bool measures_an_angle(const ex& e, const std::set<ex, GiNaC::ex_is_less>& angles) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return angles.count(e) > 0;
  if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    return name == "asin" || name == "acos" || name == "atan" || name == "atan2";
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {  // one angle times numbers
    std::size_t angle_factors = 0;
    for (const ex& factor : e) {
      if (is_a_number(factor)) continue;
      if (!measures_an_angle(factor, angles)) return false;
      ++angle_factors;
    }
    return angle_factors == 1;
  }
  if (GiNaC::is_a<GiNaC::add>(e)) {  // angles and numbers, at least one angle
    bool any = false;
    for (const ex& term : e) {
      if (is_a_number(term)) continue;
      if (!measures_an_angle(term, angles)) return false;
      any = true;
    }
    return any;
  }
  return false;
}

}  // namespace kinema
