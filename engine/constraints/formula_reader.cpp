#include "engine/constraints/formula_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <string_view>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/user_text.hpp"
#include "engine/base/work_count.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

// Limits (docs/limits.md).
// Parentheses (a function's among them): sin nested 38 deep in a loop gave pdflatex
// "Dimension too large" in kinema latex (its derivative's product of cosines is one line
// wider than TeX's largest dimension), 60 deep overflowed its buffer; 36 typeset everywhere
// kinema puts a formula (derive --format latex, the worked solution), 32 leaves a margin.
constexpr int kMaxDepth = 32;
// Calls whose derivatives divide (tan, asin, acos, atan, atan2, log) and powers other
// than whole ones (sqrt, a division), one inside another: each level multiplies the rows
// of the derivatives' LaTeX (a quotient of the levels' chain rule that cannot be broken
// over lines), and tan or asin nested 5 to 8 deep gave pdflatex "Dimension too large" in
// kinema latex; sin, cos, exp and abs nest up to kMaxDepth.
constexpr int kMaxFunctionNesting = 3;
constexpr int kMaxSignRun = 10;                ///< + and - signs in a row (each one more level of the parser)
constexpr std::size_t kMaxLiteralLength = 100;  ///< characters of one number
constexpr std::size_t kMaxLiteralExponentDigits = 4;  ///< digits of its exponent (1e9999 at most)
constexpr double kMaxExactDigits = 400;        ///< decimal digits of an exact power of numbers
constexpr double kMaxExponent = 1000;          ///< magnitude of a numeric exponent
// Terms of the formula multiplied out: the derivation expands the equations and their
// derivatives, whose coefficients grow with the power: (theta3 + theta4 + 1)^100 (5,151
// terms) took 27-36 s to derive and past 120 s in latex, ^80 12-16 s; ^20 (231 terms) takes
// 1 s in latex. A kinematic formula has tens of terms (the samples' at most a few).
constexpr double kMaxExpandedTerms = 250;

// Functions the tape compiles (sqrt and powers are powers, not functions).
const std::set<std::string>& compiled_functions() {
  static const std::set<std::string> names = {"sin", "cos", "tan", "exp", "log", "abs",
                                              "asin", "acos", "atan", "atan2"};
  return names;
}

bool is_name_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_name_part(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// What a formula is written with: names, numbers, operators, parentheses, commas and
// spaces. GiNaC's parser would take more: '#' starts a comment there (the rest of the
// formula was dropped without a word), and a byte past ASCII was shown half a character.
bool is_formula_character(char c) {
  return is_name_part(c) || std::string_view(" \t\r\n+-*/^().,").find(c) != std::string_view::npos;
}

[[noreturn]] void refuse_character(const std::string& formula, std::size_t at, const std::string& context) {
  std::size_t last = at;  // the whole UTF-8 character, not half of it
  next_code_point(formula, last);
  const std::string character = formula.substr(at, last - at + 1);
  const std::string why = character == "#" ? "; a comment goes after the closing quote: x = \"...\"  # comment"
                          : character == "{" || character == "}" || character == "[" || character == "]"
                              ? " (lists and matrices are not read); group with ( )"
                          : character == "\u00b0"
                              ? "; units are not written inside a formula: give the angle its own parameter "
                                "(beta = \"30 deg\") and use its name, or write radians (30*Pi/180)"
                              : "; formulas are written with names, numbers, + - * / ^ ( ) and commas";
  throw InputError(context + ": \"" + character + "\" is not part of a formula in \"" + formula + "\"" + why);
}

void check_shape(const std::string& formula, const std::string& context) {
  int depth = 0, signs = 0;
  for (std::size_t i = 0; i < formula.size(); ++i) {
    const char c = formula[i];
    if (!is_formula_character(c)) refuse_character(formula, i, context);
    // GiNaC's parser reads each sign of "---a" by recursion, as it does a parenthesis:
    // 10,000 signs overflowed the stack (a crash).
    if (c == '+' || c == '-') {
      if (++signs > kMaxSignRun) {
        throw InputError(context + ": the formula has more than " + std::to_string(kMaxSignRun) +
                         " + and - signs in a row; write one sign (\"--a\" is \"a\")");
      }
    } else if (c != ' ' && c != '\t') {
      signs = 0;
    }
    if (c == '(' && ++depth > kMaxDepth) {
      throw InputError(context + ": the formula nests parentheses (function calls among them) more than " +
                       std::to_string(kMaxDepth) + " deep, more than its derivatives can be typeset in LaTeX; write "
                       "it more simply");
    }
    if (c == ')') --depth;
    if (c == '(' && i > 0 && is_name_part(formula[i - 1])) {
      const std::size_t next = formula.find_first_not_of(" \t", i + 1);
      if (next != std::string::npos && formula[next] == ')') {
        throw InputError(context + ": a function is called with no argument in \"" + formula +
                         "\"; write its argument, e.g. sin(theta2)");
      }
    }
  }
}

// The formula with each number literal replaced by a placeholder name, so that GiNaC's
// parser evaluates no arithmetic on numbers before their sizes are checked.
struct ShieldedFormula {
  std::string text;
  std::vector<std::string> literals;
};

ShieldedFormula shield_numbers(const std::string& formula, const std::string& prefix, const std::string& context) {
  ShieldedFormula shielded;
  const std::size_t n = formula.size();
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i;
    if (is_name_start(formula[i])) {
      while (j < n && is_name_part(formula[j])) ++j;
      shielded.text += formula.substr(i, j - i);
    } else if (is_digit(formula[i]) || (formula[i] == '.' && i + 1 < n && is_digit(formula[i + 1]))) {
      while (j < n && (is_digit(formula[j]) || formula[j] == '.')) ++j;
      if (j < n && (formula[j] == 'e' || formula[j] == 'E')) {
        std::size_t k = j + 1;
        if (k < n && (formula[k] == '+' || formula[k] == '-')) ++k;
        if (k < n && is_digit(formula[k])) {
          j = k;
          while (j < n && is_digit(formula[j])) ++j;
          // CLN builds 10^exponent to read the number: 1e(78 digits) never ends.
          if (j - k > kMaxLiteralExponentDigits) {
            throw InputError(context + ": the number " + formula.substr(i, std::min<std::size_t>(j - i, 30)) +
                             "... has an exponent of more than " + std::to_string(kMaxLiteralExponentDigits) +
                             " digits; numbers are at most about 1e308");
          }
        }
      }
      const std::string literal = formula.substr(i, j - i);
      if (std::count(literal.begin(), literal.end(), '.') > 1) {
        throw InputError(context + ": \"" + literal.substr(0, 30) + "\" in \"" + formula +
                         "\" is not a number (more than one decimal point)");
      }
      if (literal.size() > kMaxLiteralLength) {
        throw InputError(context + ": a number in \"" + formula.substr(0, 40) + "...\" has more than " +
                         std::to_string(kMaxLiteralLength) + " characters; write it with an exponent (1.5e300)");
      }
      shielded.text += " " + prefix + std::to_string(shielded.literals.size()) + " ";
      shielded.literals.push_back(literal);
    } else {
      shielded.text += formula[i];
      ++j;
    }
    i = j;
  }
  return shielded;
}

// Decimal digits of the larger of numerator and denominator (real and imaginary parts).
double exact_digits(const GiNaC::numeric& x) {
  auto digits = [](const GiNaC::numeric& r) {
    const double bits = std::max(GiNaC::abs(r.numer()).int_length(), GiNaC::abs(r.denom()).int_length());
    return bits * std::log10(2.0);
  };
  return std::max(digits(x.real()), digits(x.imag()));
}

// Numbers put back bottom-up; each power is checked before GiNaC evaluates it.
class RestoreNumbers : public GiNaC::map_function {
 public:
  RestoreNumbers(const GiNaC::exmap& numbers, const std::string& formula, const std::string& context)
      : numbers_(numbers), formula_(formula), context_(context) {}

  ex operator()(const ex& e) override {
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      const auto found = numbers_.find(e);
      return found == numbers_.end() ? e : found->second;
    }
    if (GiNaC::is_a<GiNaC::power>(e)) {
      const ex base = (*this)(e.op(0));
      const ex exponent = (*this)(e.op(1));
      check_power(base, exponent);
      return GiNaC::pow(base, exponent);
    }
    return e.map(*this);
  }

 private:
  const GiNaC::exmap& numbers_;
  const std::string& formula_;
  const std::string& context_;

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(context_ + ": " + why + " in \"" + formula_ + "\"; write it more simply");
  }

  void check_power(const ex& base, const ex& exponent) const {
    // GiNaC throws on 0^0 and 0^-1 as it evaluates, and 0^theta3 there or in its
    // derivative (an "internal error" before).
    if (base.is_zero() && !(GiNaC::is_a<GiNaC::numeric>(exponent) && GiNaC::ex_to<GiNaC::numeric>(exponent).is_real() &&
                            GiNaC::ex_to<GiNaC::numeric>(exponent).is_positive())) {
      const bool bare = GiNaC::is_a<GiNaC::symbol>(exponent) || GiNaC::is_a<GiNaC::function>(exponent) ||
                        (GiNaC::is_a<GiNaC::numeric>(exponent) && !GiNaC::ex_to<GiNaC::numeric>(exponent).is_negative());
      fail("the power 0^" + (bare ? shown(exponent) : "(" + shown(exponent) + ")") +
           " is undefined where its exponent is 0 or negative");
    }
    if (!GiNaC::is_a<GiNaC::numeric>(exponent)) return;
    const GiNaC::numeric& x = GiNaC::ex_to<GiNaC::numeric>(exponent);
    const double magnitude = std::hypot(x.real().to_double(), x.imag().to_double());
    if (!(magnitude <= kMaxExponent)) {
      fail("the exponent " + shown(exponent) + " is larger than " + std::to_string(int(kMaxExponent)));
    }
    if (!GiNaC::is_a<GiNaC::numeric>(base)) return;
    const GiNaC::numeric& b = GiNaC::ex_to<GiNaC::numeric>(base);
    if (b.is_crational() && exact_digits(b) * magnitude > kMaxExactDigits) {
      fail("the power " + shown(base) + "^" + shown(exponent) + " has more than " +
           std::to_string(int(kMaxExactDigits)) + " digits");
    }
  }

  static std::string shown(const ex& e) {
    std::ostringstream out;
    out << e;
    std::string text = out.str();
    return text.size() > 30 ? text.substr(0, 27) + "..." : text;
  }
};

// How many terms the formula has once multiplied out (an upper estimate, capped),
// checked at every node so that a large power inside a function is caught too.
double expanded_terms(const ex& e, const std::string& formula, const std::string& context) {
  double terms = 1;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    terms = 0;
    for (const ex& term : e) terms += expanded_terms(term, formula, context);
  } else if (GiNaC::is_a<GiNaC::mul>(e)) {
    for (const ex& factor : e) terms *= expanded_terms(factor, formula, context);
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    const double base = expanded_terms(e.op(0), formula, context);
    expanded_terms(e.op(1), formula, context);
    if (GiNaC::is_a<GiNaC::numeric>(e.op(1)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer()) {
      // Terms of (t1 + ... + tk)^n: C(n + k - 1, k - 1).
      const double n = std::fabs(GiNaC::ex_to<GiNaC::numeric>(e.op(1)).to_double());
      for (double i = 1; i < base && terms <= kMaxExpandedTerms; ++i) terms = terms * (n + i) / i;
    }
  } else {
    for (const ex& argument : e) expanded_terms(argument, formula, context);
  }
  if (terms > kMaxExpandedTerms) {
    throw InputError(context + ": the formula \"" + formula.substr(0, 60) + (formula.size() > 60 ? "..." : "") +
                     "\" multiplies out to more than " + std::to_string(int(kMaxExpandedTerms)) +
                     " terms; write it more simply");
  }
  return terms;
}

// A number past the largest double (1e400, 10^399, 1e200*1e200 as GiNaC folds it)
// would reach the evaluator and the printers as inf.
void check_numbers_finite(const ex& e, const std::string& formula, const std::string& context) {
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it) {
    if (!GiNaC::is_a<GiNaC::numeric>(*it)) continue;
    const GiNaC::numeric& x = GiNaC::ex_to<GiNaC::numeric>(*it);
    bool finite = false;
    try {
      finite = std::isfinite(x.real().to_double()) && std::isfinite(x.imag().to_double());
    } catch (const std::exception&) {  // CLN's overflow of the conversion
    }
    if (!finite) {
      throw InputError(context + ": a number in \"" + formula.substr(0, 60) + (formula.size() > 60 ? "..." : "") +
                       "\" is larger than the largest number kinema computes with (about 1.8e308)");
    }
  }
}

void check_functions(const ex& e, const std::string& formula, const std::string& context) {
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it) {
    if (!GiNaC::is_a<GiNaC::function>(*it)) continue;
    const std::string name = GiNaC::ex_to<GiNaC::function>(*it).get_name();
    if (!compiled_functions().count(name)) {
      throw InputError(context + ": the function " + name + "(...) in \"" + formula +
                       "\" is not supported; formulas may use " + understood_functions());
    }
  }
}

// How deep calls of dividing functions and powers other than whole ones nest in e.
int dividing_nesting(const ex& e) {
  bool dividing = false;
  if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    dividing = name != "sin" && name != "cos" && name != "exp" && name != "abs";
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    dividing = !(GiNaC::is_a<GiNaC::numeric>(e.op(1)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_pos_integer());
  }
  int deepest = 0;
  for (std::size_t i = 0; i < e.nops(); ++i) deepest = std::max(deepest, dividing_nesting(e.op(i)));
  return deepest + (dividing ? 1 : 0);
}

void check_function_nesting(const ex& e, const std::string& context) {
  if (dividing_nesting(e) <= kMaxFunctionNesting) return;
  throw InputError(context + ": the formula nests tan, asin, acos, atan, atan2, log, sqrt, divisions or fractional "
                   "powers one inside another more than " + std::to_string(kMaxFunctionNesting) +
                   " deep, more than its derivatives can be typeset in LaTeX (sin, cos, exp and abs may nest " +
                   std::to_string(kMaxDepth) + " deep); write it more simply");
}

// GiNaC's parse error in kinema's words: its line and column are always 0 and its
// tokens are named as its lexer sees them ("EOF", a number's placeholder).
std::string parse_failure(std::string why, const std::string& placeholder) {
  why = why.substr(0, why.find('\n'));
  // GiNaC evaluates numbers while it reads, and says so in its own terms
  // ("power::eval(): division by zero", "log_eval(): log(0)", "tan_eval(): simple pole").
  if (why.find("division by zero") != std::string::npos) {
    return "it divides by zero whatever the values (a denominator such as (a-a) or 0); write it without that division";
  }
  if (const auto eval = why.find("_eval(): "); eval != std::string::npos && why.find("::") == std::string::npos) {
    const std::string function = why.substr(0, eval);
    if (why.find("pole") != std::string::npos) {
      return function + "(...) is infinite at the value written (a pole, as tan(Pi/2)); change its argument";
    }
    return function + "(...) is undefined at the value written (" + why.substr(eval + 9) +
           "); change its argument";
  }
  if (why.find("power should have exactly 2 operands") != std::string::npos) {
    return "a^b^c can be read two ways; write (a^b)^c or a^(b^c)";
  }
  const std::string parse_error = "parse error at line ";
  if (const auto at = why.find(parse_error); at != std::string::npos) {
    const auto colon = why.find(": ", at + parse_error.size());
    why = colon == std::string::npos ? why : why.substr(colon + 2);
  }
  const std::string got = "got: ";
  const auto at = why.find(got);
  std::string token = at == std::string::npos ? "" : why.substr(at + got.size());
  if (token.size() >= 2 && token.front() == '"' && token.back() == '"') token = token.substr(1, token.size() - 2);
  if (token.rfind(placeholder, 0) == 0) token = "a number";  // a literal, shielded
  else if (!token.empty() && token != "EOF") token = "\"" + token + "\"";
  if (token == "EOF") {
    if (why.rfind("expected ')'", 0) == 0) return "a parenthesis is not closed";
    return "it ends where a name, a number or \"(\" is needed";
  }
  if (why.rfind("expected EOF", 0) == 0) {
    return token == "\")\"" ? "a \")\" closes no parenthesis"
                            : token + " follows a complete expression; is an operator (+ - * / ^) missing before it?";
  }
  if (why.rfind("unexpected token", 0) == 0) return token + " stands where a name, a number or \"(\" is needed";
  const std::string no_function = "no function \"";
  if (why.rfind(no_function, 0) == 0) {
    const std::string name = why.substr(no_function.size(), why.find('"', no_function.size()) - no_function.size());
    if (is_compiled_function(name)) {
      return name + "(...) is called with the wrong number of arguments: " +
             (name == "atan2" ? "atan2(y, x) takes two" : name + " takes one");
    }
    return name + "(...) is not a function kinema knows (a product needs *: a*(b)); formulas may use " +
           understood_functions();
  }
  return why;
}

}  // namespace

FormulaReader::FormulaReader() : parser_(GiNaC::symtab(), /*strict=*/true) {}

void FormulaReader::define(const std::string& name, const GiNaC::ex& symbol) { parser_.get_syms()[name] = symbol; }

const GiNaC::ex* FormulaReader::defined(const std::string& name) {
  const GiNaC::symtab& names = parser_.get_syms();
  const auto found = names.find(name);
  return found == names.end() ? nullptr : &found->second;
}

GiNaC::ex FormulaReader::read(const std::string& formula, const std::string& context) {
  count_work(Work::formula_read);
  check_shape(formula, context);
  // A placeholder prefix no defined name starts with.
  std::string prefix = "kinemaNumber";
  GiNaC::symtab& names = parser_.get_syms();
  auto taken = [&] {  // the table is sorted: the first name not below the prefix tells
    const auto next = names.lower_bound(prefix);
    return next != names.end() && next->first.rfind(prefix, 0) == 0;
  };
  while (taken()) prefix += "x";
  const ShieldedFormula shielded = shield_numbers(formula, prefix, context);

  GiNaC::exmap numbers;
  std::vector<std::string> placeholders;
  struct Undefine {  // placeholders leave the table however the parse ends
    GiNaC::symtab& names;
    std::vector<std::string>& defined;
    ~Undefine() {
      for (const auto& name : defined) names.erase(name);
    }
  } undefine{names, placeholders};
  ex e;
  try {
    for (std::size_t k = 0; k < shielded.literals.size(); ++k) {
      const std::string name = prefix + std::to_string(k);
      const GiNaC::symbol placeholder(name);
      names[name] = placeholder;
      placeholders.push_back(name);
      numbers[placeholder] = GiNaC::numeric(shielded.literals[k].c_str());
    }
    const ex parsed = parser_(shielded.text);
    check_functions(parsed, formula, context);
    RestoreNumbers restore(numbers, formula, context);
    e = restore(parsed);
    check_numbers_finite(e, formula, context);
    expanded_terms(e, formula, context);
    check_function_nesting(e, context);
  } catch (const InputError&) {
    throw;
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
    throw InputError(context + ": cannot read the formula \"" + formula + "\": " + parse_failure(why, prefix));
  }
  return e;
}

bool is_compiled_function(const std::string& name) { return compiled_functions().count(name) > 0; }

double formula_value(const GiNaC::ex& formula, const GiNaC::exmap& values, const std::string& context,
                     const std::string& text, const std::string& hint) {
  GiNaC::ex number;
  try {
    GiNaC::exmap used;
    for (auto it = formula.preorder_begin(); it != formula.preorder_end(); ++it) {
      const auto found = GiNaC::is_a<GiNaC::symbol>(*it) ? values.find(*it) : values.end();
      if (found != values.end()) used.insert(*found);
    }
    number = GiNaC::evalf(formula.subs(used, GiNaC::subs_options::no_pattern));
  } catch (const std::exception& error) {
    throw InputError(context + " = \"" + text + "\" cannot be evaluated (" + error.what() + ")");
  }
  if (!GiNaC::is_a<GiNaC::numeric>(number) || !GiNaC::ex_to<GiNaC::numeric>(number).is_real()) {
    throw InputError(context + " = \"" + text + "\" does not evaluate to a real number" + hint);
  }
  const double value = GiNaC::ex_to<GiNaC::numeric>(number).to_double();
  if (!std::isfinite(value)) throw InputError(context + " = \"" + text + "\" is not a finite number");
  return value;
}

const char* understood_functions() {
  return "sin, cos, tan, exp, log, sqrt, abs, asin, acos, atan, atan2 and powers (^)";
}

}  // namespace kinema
