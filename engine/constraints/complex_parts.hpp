// The real and imaginary parts of a planar formula whose symbols are all real. GiNaC's
// real_part() of sin(u) asks for both parts of u, and so on down: 2^depth calls for
// nested functions (25 nested sines took minutes). Here a subexpression without I is
// real and is returned whole, so the parts cost one pass.
#pragma once

#include <ginac/ginac.h>

namespace kinema {

struct ComplexParts {
  GiNaC::ex real, imag;
};

/// Re and Im of e, every symbol real: a call without I inside is real (real_part(atan(u))
/// is atan(u)); sums, products, exp, sin and cos split as GiNaC splits them. Not expanded.
ComplexParts complex_parts(const GiNaC::ex& e);

/// complex_parts(e).real, multiplied out (multiplied_out: within its budget).
GiNaC::ex real_part_of(const GiNaC::ex& e);

/// complex_parts(e).imag, multiplied out (multiplied_out: within its budget).
GiNaC::ex imag_part_of(const GiNaC::ex& e);

}  // namespace kinema
