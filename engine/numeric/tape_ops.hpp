// The tape's operations, listed once: each with how many register operands it
// reads and its value in terms of A, B, C (operands) and E (integer exponent).
// The scalar runner, the lane runner, the C++ emitter and the web page's JavaScript
// runner are all expanded from this list, so they cannot disagree. sincos (two results
// from one argument) is the one operation outside it.
#pragma once

#include <cmath>

// X(name, operands, value as C++, value as emitted C++ text, value as JavaScript text
//   (the page's runner, tape_emitter.cpp write_tape_runner_js; integerPower is its powi))
#define KINEMA_TAPE_OPS(X)                                              \
  X(add, 2, A + B, "A + B", "A + B")                                                       \
  X(sub, 2, A - B, "A - B", "A - B")                                                       \
  X(mul, 2, A * B, "A * B", "A * B")                                                       \
  X(div, 2, A / B, "A / B", "A / B")                                                       \
  X(neg, 1, -A, "-A", "-A")                                                                \
  X(square, 1, A * A, "A * A", "A * A")                                                    \
  X(powi, 1, ::kinema::integer_power(A, E), "std::pow(A, E)", "integerPower(A, E)")        \
  X(pow, 2, std::pow(A, B), "std::pow(A, B)", "Math.pow(A, B)")                            \
  X(tan, 1, std::tan(A), "std::tan(A)", "Math.tan(A)")                                     \
  X(exp, 1, std::exp(A), "std::exp(A)", "Math.exp(A)")                                     \
  X(log, 1, std::log(A), "std::log(A)", "Math.log(A)")                                     \
  X(sqrt, 1, std::sqrt(A), "std::sqrt(A)", "Math.sqrt(A)")                                 \
  X(abs, 1, std::fabs(A), "std::fabs(A)", "Math.abs(A)")                                   \
  X(atan2, 2, std::atan2(A, B), "std::atan2(A, B)", "Math.atan2(A, B)")                    \
  X(asin, 1, std::asin(A), "std::asin(A)", "Math.asin(A)")                                 \
  X(acos, 1, std::acos(A), "std::acos(A)", "Math.acos(A)")                                 \
  X(atan, 1, std::atan(A), "std::atan(A)", "Math.atan(A)")                                 \
  X(mul_add, 3, A * B + C, "A * B + C", "A * B + C")                                       \
  X(mul_sub, 3, A * B - C, "A * B - C", "A * B - C")                                       \
  X(sub_mul, 3, C - A * B, "C - A * B", "C - A * B")                                      

namespace kinema {

/// base^exponent by squaring (the tape's integer powers).
inline double integer_power(double base, int exponent) {
  double result = 1.0;
  for (int e = exponent < 0 ? -exponent : exponent; e; e >>= 1, base *= base)
    if (e & 1) result *= base;
  return exponent < 0 ? 1.0 / result : result;
}

}  // namespace kinema
