// Reads the formulas of a mechanism file with GiNaC's parser, refusing first what
// the parser or what follows cannot take safely (limits: docs/limits.md):
// parentheses nested past 100 (its recursion overflows the stack near 8,000), a
// call with no argument ("sin()" dereferences a null argument), a number literal of
// more than 100 characters, a power of numbers whose exact value would have more
// than 400 digits (GiNaC evaluates 10^(10^10) exactly while parsing: gigabytes),
// an exponent past 1000 in magnitude, a formula that would expand to more than
// 250 terms, functions whose derivatives divide (tan, log, sqrt, ...) nested more than
// 3 deep, and functions the evaluator does not compile.
#pragma once

#include <ginac/ginac.h>

#include <string>

namespace kinema {

class FormulaReader {
 public:
  FormulaReader();

  /// Makes `name` a symbol formulas may use.
  void define(const std::string& name, const GiNaC::ex& symbol);

  /// The symbol defined as `name`, or nullptr: a name is its symbol without its text read.
  const GiNaC::ex* defined(const std::string& name);

  /// The formula as an expression; throws InputError(context + ": ...") naming what is wrong.
  /// Counted (engine/base/work_count: Work::formula_read).
  GiNaC::ex read(const std::string& formula, const std::string& context);

 private:
  GiNaC::parser parser_;
};

/// The value of `formula` (written `text`) with the numbers of `values` put in for its
/// symbols (only those it uses: subs walks its whole map, quadratic in the parameters).
/// InputError(context + " = \"text\" ...") when GiNaC cannot evaluate it (CLN's float
/// overflow, a pole such as a length of 0 under a division), or it is not a real,
/// finite number (`hint` says why that may be).
double formula_value(const GiNaC::ex& formula, const GiNaC::exmap& values, const std::string& context,
                     const std::string& text, const std::string& hint = "");

/// Functions a formula may use (the compiled evaluator runs each of them).
const char* understood_functions();
/// True for a function the compiled evaluator runs ("sin", "atan2", ...).
bool is_compiled_function(const std::string& name);

}  // namespace kinema
