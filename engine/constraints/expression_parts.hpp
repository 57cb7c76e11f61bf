// Small helpers for taking GiNaC expressions apart, shared by the derivation
// and the printers.
#pragma once

#include <ginac/ginac.h>

#include <sstream>
#include <string>

namespace kinema {

/// An expression in GiNaC's own syntax (what its parser reads back).
inline std::string to_text(const GiNaC::ex& e) {
  std::ostringstream out;
  out << e;
  return out.str();
}

/// True for a call of the named function, e.g. is_function(e, "sin").
inline bool is_function(const GiNaC::ex& e, const char* name) {
  return GiNaC::is_a<GiNaC::function>(e) && GiNaC::ex_to<GiNaC::function>(e).get_name() == name;
}

/// A loop term as a link vector: length * exp(I*angle). polar is false when the
/// term has no exp factor (then length is the whole term).
struct LinkVector {
  GiNaC::ex length = 1;
  GiNaC::ex angle = 0;
  bool polar = false;
};

inline LinkVector split_link_vector(const GiNaC::ex& term) {
  LinkVector v;
  const auto take = [&](const GiNaC::ex& factor) {
    if (is_function(factor, "exp") && !v.polar) {
      v.polar = true;
      v.angle = (factor.op(0) / GiNaC::I).expand();
    } else {
      v.length *= factor;
    }
  };
  if (GiNaC::is_a<GiNaC::mul>(term)) {
    for (const GiNaC::ex& f : term) take(f);
  } else {
    take(term);
  }
  return v;
}

}  // namespace kinema
