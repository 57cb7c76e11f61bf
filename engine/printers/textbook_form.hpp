// Formulas as a textbook prints them, in text (GiNaC syntax, so they read back) or
// LaTeX: in a product numbers, then lengths and other parameters, then coordinates, then
// rates, then functions (c*omega4*sin(theta4)); a sum's terms by the coordinates they
// carry (theta2 before theta3); a difference inside sin or cos with its positive term first
// (sin(theta3 - theta4), never sin(-theta4 + theta3)), the sign moved out of an odd
// function; in LaTeX \sin\theta_{3} for a single symbol, \frac for quotients. GiNaC's own
// order is its internal hash order: fine to compute with, not to read.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <memory>
#include <functional>
#include <string>
#include <vector>

#include "engine/constraints/constraint_system.hpp"

namespace kinema {

/// Roughly how many glyphs wide a LaTeX math formula prints (for breaking lines).
double latex_width(const std::string& latex);

/// The name of the command whose backslash is at `backslash` ("sin" of "\\sin x"; empty for
/// "\\," and the like); `end` is set past the name.
std::string latex_command_name(const std::string& latex, std::size_t backslash, std::size_t& end);

class TextbookForm {
 public:
  enum class Style { text, latex };
  /// Text to print in place of a symbol (a worked solution's numbers), keyed by the symbol.
  using SymbolTexts = std::map<GiNaC::ex, std::string, GiNaC::ex_is_less>;

  /// The order of the system's symbols: parameters as in the file, then the input and the
  /// unknowns, then their rates and second rates.
  explicit TextbookForm(const ConstraintSystem& system);
  /// Without a system: every symbol ordered as a parameter, by its name.
  TextbookForm();

  std::string operator()(const GiNaC::ex& e, Style style, const SymbolTexts* texts = nullptr) const;

  /// A solved rate of `unknown` (its angle symbol): a sine difference in the denominator
  /// starts with the unknown's angle, and a minus sign of the whole quotient goes into a
  /// sine difference of the numerator, as Norton writes
  /// omega3 = a*omega2*sin(theta4 - theta2)/(b*sin(theta3 - theta4)).
  std::string solved(const GiNaC::ex& e, const GiNaC::ex& unknown, Style style,
                     const SymbolTexts* texts = nullptr) const;

  /// LaTeX of a formula (a solved rate of `unknown`, or any formula when it is 0) as
  /// lines of at most `budget` glyphs or so: a sum's terms over lines, a long quotient as
  /// \frac{K}{D}\bigl(terms...\bigr); one line when it fits or cannot be broken.
  std::vector<std::string> latex_lines(const GiNaC::ex& e, const GiNaC::ex& unknown, const SymbolTexts* texts,
                                       double budget) const;

  /// One component (x: real part, y: imaginary part) of a planar loop with its terms in
  /// the order the file writes them: a*cos(theta2) + b*cos(theta3) - c*cos(theta4) - d.
  /// Empty for a group without written terms.
  std::string loop_component(const EquationGroup& group, bool imaginary, Style style) const;
  /// Equation `row` of the system (= 0 left out): a planar loop's x or y component with
  /// its terms as written, anything else in textbook form.
  std::string equation(const ConstraintSystem& system, std::size_t row, Style style) const;
  /// The loop as a vector sum, its terms as written: AB*exp(I*phi) - BC*exp(I*phi2) - (La + I*Lb).
  std::string loop_vector(const EquationGroup& group, Style style) const;

  /// Floats in their shortest form that reads back as the same double (0.296198 or
  /// 0.29619813272602) instead of 6 significant digits: for formulas whose floats were
  /// rounded to the digits they need (a spatial chain at its instant); in LaTeX a
  /// number's denominator with a sum goes in front (\frac{1}{2}\cos\alpha\,(...)).
  void set_exact_floats(bool exact) { exact_floats_ = exact; }

 private:
  bool exact_floats_ = false;
  // A formula's text independent of GiNaC's order of operands and of where it puts a sign
  // (the last tie-break of every order: the same print from every build).
  struct Canonical {
    std::string text;
    bool negated = false;
  };
  struct Memo;
  std::shared_ptr<Memo> memo_;  // shared by copies: what it holds does not depend on exact_floats_
  Canonical canonical(const GiNaC::ex& e) const;
  Canonical canonical_of_parts(const GiNaC::ex& e) const;
  std::string canonical_text(const GiNaC::ex& e) const;
  std::string unsigned_text(const GiNaC::ex& e) const;
  struct Key {
    int rank;   // 0 numbers, 1 parameters, 2 coordinates, 3 rates, 4 functions, 5 other
    int index;  // order within the rank
  };
  std::map<GiNaC::ex, Key, GiNaC::ex_is_less> keys_;
  std::map<GiNaC::ex, int, GiNaC::ex_is_less> coordinate_of_;  // symbol -> its coordinate's index

  struct Context;
  struct Factor {
    GiNaC::ex base, exponent;
    bool flipped = false;  // a trigonometric function of the negated argument
  };
  // A product as numerator and denominator factors, each sum's and each trigonometric
  // difference's sign taken out into `negative`.
  struct ProductParts {
    std::vector<Factor> numerator, denominator;
    bool negative = false;
  };
  ProductParts product_parts(const GiNaC::ex& e, const GiNaC::ex* preferred) const;
  Key key_of(const GiNaC::ex& factor) const;
  int coordinate_key(const GiNaC::ex& term) const;
  void sort_terms(std::vector<GiNaC::ex>& terms,
                  const std::function<int(const GiNaC::ex&, const GiNaC::ex&)>& first) const;
  int parameter_key(const GiNaC::ex& term) const;
  std::string render(const GiNaC::ex& e, int precedence, Context& c) const;
  std::string render_sum(const GiNaC::ex& e, int precedence, Context& c) const;
  std::pair<bool, std::string> render_product(const GiNaC::ex& e, Context& c) const;
  std::string render_power(const GiNaC::ex& base, const GiNaC::ex& exponent, Context& c) const;
  std::string render_function(const GiNaC::ex& f, const GiNaC::ex& argument, Context& c) const;
  std::string render_number(const GiNaC::numeric& n, Context& c) const;
  std::string render_argument(const GiNaC::ex& argument, Context& c) const;
  std::vector<std::string> factor_pieces(const GiNaC::ex& product, const std::string& sign, Context& c,
                                         double budget) const;
  bool leads_negative(const GiNaC::ex& sum, const GiNaC::ex* first) const;
  bool sum_leads_negative(const GiNaC::ex& sum) const;
};

}  // namespace kinema
