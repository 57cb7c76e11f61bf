// What a formula measures, told from its symbols: the power of length it carries
// (a length 1, an angle or plain number 0). The front ends check with it that a loop
// or point is a length and that a turn or a function's argument is not.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <optional>
#include <set>
#include <string>

namespace kinema {

/// Length exponent of a formula ("a*exp(I*theta)" -> 1, "theta" -> 0);
/// nullopt where it cannot be known (plain-number parameters, bare constants).
class LengthPower {
 public:
  using Powers = std::map<GiNaC::ex, int, GiNaC::ex_is_less>;
  // Refers to the caller's table (a copy per parameter made 10,000 parameters quadratic).
  explicit LengthPower(const Powers& powers) : powers_(powers) {}

  /// Throws InputError(context + why) on a mismatch.
  std::optional<int> of(const GiNaC::ex& e, const std::string& context) const;

  /// "length", "length^2", "angle or plain number".
  static std::string describe(int power);

 private:
  const Powers& powers_;
};

/// Whether a formula measures an angle: one of `angles` (the angle parameters' symbols),
/// an inverse circular function (asin, acos, atan, atan2), a number times one, or a sum
/// of them and numbers ("theta + Pi/2"). A number alone, or an angle's sine, is not.
bool measures_an_angle(const GiNaC::ex& e, const std::set<GiNaC::ex, GiNaC::ex_is_less>& angles);

}  // namespace kinema
