#include "engine/printers/textbook_form.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <sstream>
#include <unordered_map>
#include <vector>

#include "engine/base/number_format.hpp"
#include "engine/constraints/complex_parts.hpp"
#include "engine/constraints/expansion.hpp"
#include "engine/constraints/expression_parts.hpp"

namespace kinema {

using GiNaC::ex;

namespace {

constexpr int kSum = 1, kProduct = 2, kPower = 3;
// A product up to this many lines wide stays on one line (the samples' longest terms, a
// line and a half, print as before); a wider one is broken between its factors, and
// between the terms of a wide sum among them (TeX stops at a row wider than 16,383 pt).
constexpr double kUnbrokenProductLines = 8;

bool is_odd_function(const ex& e) { return is_function(e, "sin") || is_function(e, "tan"); }
bool is_trig(const ex& e) { return is_odd_function(e) || is_function(e, "cos"); }

// GiNaC's own printing, as a fallback for what the textbook form does not cover.
std::string ginac_text(const ex& e, bool latex) {
  std::ostringstream out;
  if (latex) out << GiNaC::latex;
  out << e;
  return out.str();
}

// A canonical text longer than this stands as a digest of itself in the texts of the
// formulas around it, so that each text is built from parts of bounded size: a formula's
// derivatives share their subexpressions, and written out in full the texts of tan
// nested 8 deep took minutes to build. Deterministic (from the text, not from GiNaC's
// hashes), so the order stays the same from every build; the samples' texts are shorter.
constexpr std::size_t kCanonicalTextBudget = 2048;

std::string bounded(std::string text) {
  if (text.size() <= kCanonicalTextBudget) return text;
  std::uint64_t digest = 14695981039346656037ull;  // FNV-1a
  for (const char ch : text) digest = (digest ^ static_cast<unsigned char>(ch)) * 1099511628211ull;
  char hex[24];
  std::snprintf(hex, sizeof hex, "#%016llx", static_cast<unsigned long long>(digest));
  return hex;
}

}  // namespace

// What the printer works out once for each subexpression however often it occurs: the
// derivatives of nested functions repeat a subexpression once per level (tan nested 8
// deep took past 60 s to print, each level's order worked out again below it).
struct TextbookForm::Memo {
  std::unordered_map<ex, Canonical, std::hash<ex>, GiNaC::ex_is_equal> canonical;
  std::unordered_map<ex, int, std::hash<ex>, GiNaC::ex_is_equal> coordinate, parameter;
};

TextbookForm::TextbookForm() : memo_(std::make_shared<Memo>()) {}

TextbookForm::Canonical TextbookForm::canonical(const ex& e) const {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return {ginac_text(e, false), false};
  const auto known = memo_->canonical.find(e);
  if (known != memo_->canonical.end()) return known->second;
  Canonical result = canonical_of_parts(e);
  result.text = bounded(std::move(result.text));
  memo_->canonical.emplace(e, result);
  return result;
}

// A formula's text independent of GiNaC's own order of operands and of the signs it
// chooses, which follow hashes of addresses and symbol serials and so differ from one
// build (or one load) to another: sums and products with their operands sorted by this
// text, and the sign that GiNaC may put either inside or outside a term (sin(x - y) or
// -sin(y - x), (x - y)*w or -(y - x)*w) taken out as `negated`, so that e and -e have
// the same text. The last tie-break of every order below: a formula prints the same
// from every build.
TextbookForm::Canonical TextbookForm::canonical_of_parts(const ex& e) const {
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    GiNaC::numeric n = GiNaC::ex_to<GiNaC::numeric>(e);
    const GiNaC::numeric lead = n.real().is_zero() ? n.imag() : n.real();
    const bool negated = lead.is_negative();
    return {ginac_text(negated ? ex(-n) : ex(n), false), negated};
  }
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    bool negated = false;
    std::vector<std::string> parts;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const Canonical factor = canonical(e.op(i));
      negated = negated != factor.negated;
      if (factor.text != "1") parts.push_back(factor.text);
    }
    std::sort(parts.begin(), parts.end());
    if (parts.size() == 1) return {parts.front(), negated};  // -x: the text of x
    std::string text = "mul(";
    for (const std::string& part : parts) text += part + ",";
    return {text + ")", negated};
  }
  if (GiNaC::is_a<GiNaC::add>(e)) {
    // The terms with their signs, and with the opposite signs: the smaller of the two.
    std::vector<std::string> plus, minus;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const Canonical term = canonical(e.op(i));
      plus.push_back((term.negated ? "-" : "+") + term.text);
      minus.push_back((term.negated ? "+" : "-") + term.text);
    }
    std::sort(plus.begin(), plus.end());
    std::sort(minus.begin(), minus.end());
    const bool negated = minus < plus;
    std::string text = "add(";
    for (const std::string& term : negated ? minus : plus) text += term + ",";
    return {text + ")", negated};
  }
  if (GiNaC::is_a<GiNaC::power>(e)) {
    const Canonical base = canonical(e.op(0)), exponent = canonical(e.op(1));
    const std::string power = (exponent.negated ? "-" : "") + exponent.text;
    const bool integer = GiNaC::is_a<GiNaC::numeric>(e.op(1)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer();
    if (!integer) return {"pow(" + std::string(base.negated ? "-" : "") + base.text + "," + power + ")", false};
    return {"pow(" + base.text + "," + power + ")", base.negated && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_odd()};
  }
  if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    if (e.nops() == 1 && (is_trig(e))) {  // sin(-x) = -sin(x), cos(-x) = cos(x)
      const Canonical argument = canonical(e.op(0));
      return {name + "(" + argument.text + ")", argument.negated && is_odd_function(e)};
    }
    std::string text = name + "(";
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const Canonical argument = canonical(e.op(i));
      text += (argument.negated ? "-" : "") + argument.text + ",";
    }
    return {text + ")", false};
  }
  return {ginac_text(e, false), false};
}

namespace {

// -sum term by term: expand() would also multiply out the powers of sums among them.
ex negated_terms(const ex& sum) {
  ex negated = 0;
  for (std::size_t i = 0; i < sum.nops(); ++i) negated += -sum.op(i);
  return negated;
}

}  // namespace

// The tie-break key of a term or factor: its canonical text, then its sign (after a
// character below every other, so that the text alone decides first).
std::string TextbookForm::canonical_text(const ex& e) const {
  const Canonical c = canonical(e);
  return c.text + (c.negated ? "\x02" : "\x01");
}

// The canonical text alone: the same for e and -e (which term of a difference leads).
std::string TextbookForm::unsigned_text(const ex& e) const { return canonical(e).text; }

struct TextbookForm::Context {
  Style style;
  const SymbolTexts* texts;
  const ex* preferred = nullptr;  // a difference in a function argument starts with it
  bool argument = false;          // rendering a function's argument: positive terms first
  bool bare_numbers = false;      // inside a function's argument: (30^\circ) as 30^\circ
  bool latex() const { return style == Style::latex; }
};

TextbookForm::TextbookForm(const ConstraintSystem& system) : TextbookForm() {
  int index = 0;
  for (const SystemParameter& p : system.parameters) keys_[p.symbol] = {1, index++};
  std::vector<const Coordinate*> coordinates = {&system.input};
  for (const Coordinate& q : system.unknowns) coordinates.push_back(&q);
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    const Coordinate& q = *coordinates[i];
    keys_[q.symbol] = {2, int(i)};
    keys_[q.rate] = {3, int(2 * i)};
    keys_[q.second_rate] = {3, int(2 * i + 1)};
    for (const ex& s : {ex(q.symbol), ex(q.rate), ex(q.second_rate)}) coordinate_of_[s] = int(i);
  }
}

TextbookForm::Key TextbookForm::key_of(const ex& factor) const {
  if (GiNaC::is_a<GiNaC::numeric>(factor)) return {0, GiNaC::ex_to<GiNaC::numeric>(factor).is_real() ? 0 : 1};
  if (GiNaC::is_a<GiNaC::symbol>(factor)) {
    const auto known = keys_.find(factor);
    return known != keys_.end() ? known->second : Key{1, INT_MAX};
  }
  if (GiNaC::is_a<GiNaC::power>(factor)) return key_of(factor.op(0));
  if (GiNaC::is_a<GiNaC::function>(factor)) return {4, coordinate_key(factor)};
  // A sum of parameters (CD + CE) is a length like the others; other sums go last.
  if (GiNaC::is_a<GiNaC::add>(factor) && coordinate_key(factor) == INT_MAX) return {1, parameter_key(factor)};
  return {5, 0};
}

// The smallest file index among a term's parameters (INT_MAX without parameters).
int TextbookForm::parameter_key(const ex& term) const {
  if (GiNaC::is_a<GiNaC::symbol>(term)) {
    const auto known = keys_.find(term);
    return known != keys_.end() && known->second.rank == 1 ? known->second.index : INT_MAX;
  }
  if (term.nops() == 0) return INT_MAX;
  const auto memo = memo_->parameter.find(term);
  if (memo != memo_->parameter.end()) return memo->second;
  int smallest = INT_MAX;
  for (std::size_t i = 0; i < term.nops(); ++i) smallest = std::min(smallest, parameter_key(term.op(i)));
  memo_->parameter.emplace(term, smallest);
  return smallest;
}

// The smallest coordinate index among a term's symbols (rates count as their
// coordinate's); INT_MAX for a term without coordinates (it goes last in a sum).
int TextbookForm::coordinate_key(const ex& term) const {
  if (GiNaC::is_a<GiNaC::symbol>(term)) {
    const auto known = coordinate_of_.find(term);
    return known != coordinate_of_.end() ? known->second : INT_MAX;
  }
  if (term.nops() == 0) return INT_MAX;
  const auto memo = memo_->coordinate.find(term);
  if (memo != memo_->coordinate.end()) return memo->second;
  int smallest = INT_MAX;
  for (std::size_t i = 0; i < term.nops(); ++i) smallest = std::min(smallest, coordinate_key(term.op(i)));
  memo_->coordinate.emplace(term, smallest);
  return smallest;
}

std::string TextbookForm::operator()(const ex& e, Style style, const SymbolTexts* texts) const {
  Context c{style, texts};
  return render(e, 0, c);
}

std::string TextbookForm::render_number(const GiNaC::numeric& n, Context& c) const {
  const auto digits = [](const GiNaC::numeric& k) {
    std::ostringstream out;
    out << k;
    return out.str();
  };
  if (n.is_integer()) return digits(n);
  if (n.is_rational()) {
    const std::string p = digits(n.numer()), q = digits(n.denom());
    return c.latex() ? "\\frac{" + p + "}{" + q + "}" : p + "/" + q;
  }
  if (n.is_real() && exact_floats_) {
    const double value = n.to_double();
    char text[64];
    for (int digits = 6; digits <= 17; ++digits) {
      std::snprintf(text, sizeof text, "%.*g", digits, value);
      if (std::strtod(text, nullptr) == value) break;
    }
    return text;
  }
  if (n.is_real()) {
    const std::string text = format_significant(n.to_double());
    return text;
  }
  return ginac_text(n, c.latex());
}

std::string TextbookForm::render(const ex& e, int precedence, Context& c) const {
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(e);
    if (n.is_real() && n.is_negative()) {
      const std::string text = "-" + render_number(-n, c);
      return precedence > kSum ? "(" + text + ")" : text;
    }
    if (n.is_real() && !n.is_integer() && precedence >= kPower) return "(" + render_number(n, c) + ")";
    return render_number(n, c);
  }
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    if (c.texts) {
      const auto text = c.texts->find(e);
      if (text != c.texts->end()) {
        const std::string& t = text->second;
        const bool bare = c.bare_numbers && t.size() > 2 && t.front() == '(' && t.back() == ')' && t[1] != '-';
        return bare ? t.substr(1, t.size() - 2) : t;
      }
    }
    return c.latex() ? GiNaC::ex_to<GiNaC::symbol>(e).get_TeX_name() : GiNaC::ex_to<GiNaC::symbol>(e).get_name();
  }
  if (GiNaC::is_a<GiNaC::add>(e)) return render_sum(e, precedence, c);
  // A power of a sum goes through render_product too, to take a sign out of the sum.
  const bool quotient = GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1)) &&
                        (GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_negative() ||
                         (GiNaC::is_a<GiNaC::add>(e.op(0)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer()));
  if (GiNaC::is_a<GiNaC::mul>(e) || quotient) {
    const auto [negative, text] = render_product(e, c);
    const bool bare_quotient = !c.latex() && text.find('/') != std::string::npos;
    if (negative) return precedence > kSum ? "(-" + text + ")" : "-" + text;
    return precedence >= kPower || (bare_quotient && precedence >= kProduct) ? "(" + text + ")" : text;
  }
  if (GiNaC::is_a<GiNaC::power>(e)) return render_power(e.op(0), e.op(1), c);
  if (GiNaC::is_a<GiNaC::function>(e)) {
    if (is_trig(e)) {  // alone: its argument oriented, the sign of an odd function in front
      const ex argument = e.op(0);
      if (GiNaC::is_a<GiNaC::add>(argument) && leads_negative(argument, c.preferred)) {
        const std::string text = render_function(e, -argument, c);
        if (!is_odd_function(e)) return text;
        return precedence > kSum ? "(-" + text + ")" : "-" + text;
      }
    }
    return render_function(e, e.nops() > 0 ? e.op(0) : ex(0), c);
  }
  return ginac_text(e, c.latex());
}

// A sum's terms in textbook order: `first` (-1, 0, 1 as a < b, no preference, a > b)
// decides first, then the lowest coordinate, the first parameter, and the canonical text.
void TextbookForm::sort_terms(std::vector<ex>& terms, const std::function<int(const ex&, const ex&)>& first) const {
  struct Keyed {
    ex term;
    int coordinate, parameter;
    std::string text;
  };
  std::vector<Keyed> keyed;
  for (const ex& t : terms) keyed.push_back({t, coordinate_key(t), parameter_key(t), canonical_text(t)});
  std::stable_sort(keyed.begin(), keyed.end(), [&](const Keyed& a, const Keyed& b) {
    if (const int decided = first(a.term, b.term)) return decided < 0;
    if (a.coordinate != b.coordinate) return a.coordinate < b.coordinate;
    if (a.parameter != b.parameter) return a.parameter < b.parameter;
    return a.text < b.text;
  });
  for (std::size_t k = 0; k < terms.size(); ++k) terms[k] = keyed[k].term;
}

// True when a sum's first term in textbook order (as render_sum prints it outside a
// function's argument) prints with a minus sign. The same term leads -sum, with the
// other sign whatever GiNaC's form of it (a sign in front, or inside a factor).
bool TextbookForm::sum_leads_negative(const ex& sum) const {
  std::vector<ex> terms(sum.begin(), sum.end());
  sort_terms(terms, [](const ex&, const ex&) { return 0; });
  const ex& lead = terms.front();
  if (GiNaC::is_a<GiNaC::numeric>(lead))
    return GiNaC::ex_to<GiNaC::numeric>(lead).is_real() && GiNaC::ex_to<GiNaC::numeric>(lead).is_negative();
  // The sign before the cosmetic rules of render_product (-(A + B)/D as (-A - B)/D), which
  // would print a term and its negation alike; and only down the first terms, so that
  // nested sums cost once per level.
  if (GiNaC::is_a<GiNaC::mul>(lead) || GiNaC::is_a<GiNaC::power>(lead)) return product_parts(lead, nullptr).negative;
  return is_odd_function(lead) && GiNaC::is_a<GiNaC::add>(lead.op(0)) && leads_negative(lead.op(0), nullptr);
}

// True when the term that an oriented difference starts with (the preferred symbol's,
// else the one of the lowest coordinate) has a negative sign.
bool TextbookForm::leads_negative(const ex& sum, const ex* first) const {
  ex lead;  // a copy: GiNaC's iterators give temporaries
  bool found = false;
  int best = INT_MAX;
  std::string best_text;
  for (std::size_t i = 0; i < sum.nops(); ++i) {
    const ex term = sum.op(i);
    int key = coordinate_key(term);
    if (first != nullptr && term.has(*first)) key = -1;
    const std::string text = unsigned_text(term);
    if (!found || key < best || (key == best && text < best_text)) {
      lead = term;
      best = key;
      best_text = text;
      found = true;
    }
  }
  if (!found) return false;
  if (GiNaC::is_a<GiNaC::numeric>(lead)) return GiNaC::ex_to<GiNaC::numeric>(lead).is_negative();
  if (GiNaC::is_a<GiNaC::mul>(lead)) {
    const ex coefficient = lead.op(lead.nops() - 1);
    return GiNaC::is_a<GiNaC::numeric>(coefficient) && GiNaC::ex_to<GiNaC::numeric>(coefficient).is_negative();
  }
  return false;
}

std::string TextbookForm::render_sum(const ex& e, int precedence, Context& c) const {
  std::vector<ex> terms(e.begin(), e.end());
  const auto negative_term = [](const ex& t) {
    const ex k = GiNaC::is_a<GiNaC::mul>(t) ? t.op(t.nops() - 1) : t;
    return GiNaC::is_a<GiNaC::numeric>(k) && GiNaC::ex_to<GiNaC::numeric>(k).is_real() &&
           GiNaC::ex_to<GiNaC::numeric>(k).is_negative();
  };
  const bool argument = c.argument;
  c.argument = false;
  sort_terms(terms, [&](const ex& a, const ex& b) {
    if (argument && negative_term(a) != negative_term(b)) return !negative_term(a) ? -1 : 1;  // theta3 - theta4
    return 0;
  });
  std::string text;
  for (const ex& term : terms) {
    bool negative = false;
    std::string part;
    if (GiNaC::is_a<GiNaC::numeric>(term) && GiNaC::ex_to<GiNaC::numeric>(term).is_real()) {
      const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(term);
      negative = n.is_negative();
      part = render_number(negative ? -n : n, c);
    } else if (GiNaC::is_a<GiNaC::mul>(term) || GiNaC::is_a<GiNaC::power>(term)) {
      std::tie(negative, part) = render_product(term, c);
      if (!c.latex() && part.find('/') != std::string::npos && terms.size() > 1) part = "(" + part + ")";
    } else {
      part = render(term, kSum + 1, c);
      if (!part.empty() && part[0] == '-') {  // an odd function whose sign came out
        negative = true;
        part = part.substr(1);
      }
    }
    if (text.empty()) text = negative ? "-" + part : part;
    else text += (negative ? " - " : " + ") + part;
  }
  return precedence > kSum ? "(" + text + ")" : text;
}

TextbookForm::ProductParts TextbookForm::product_parts(const ex& e, const ex* preferred) const {
  std::vector<ex> factors;
  if (GiNaC::is_a<GiNaC::mul>(e)) factors.assign(e.begin(), e.end());
  else factors.push_back(e);
  GiNaC::numeric coefficient = 1;
  ProductParts parts;
  std::vector<Factor>& numerator = parts.numerator;
  std::vector<Factor>& denominator = parts.denominator;
  bool imaginary_unit = false;
  for (const ex& f : factors) {
    if (GiNaC::is_a<GiNaC::numeric>(f) && GiNaC::ex_to<GiNaC::numeric>(f).is_real()) {
      coefficient *= GiNaC::ex_to<GiNaC::numeric>(f);
    } else if (GiNaC::is_a<GiNaC::numeric>(f) && GiNaC::ex_to<GiNaC::numeric>(f).real().is_zero()) {
      coefficient *= GiNaC::ex_to<GiNaC::numeric>(f).imag();  // -I*Lb: minus, then i Lb
      imaginary_unit = true;
    } else if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<GiNaC::numeric>(f.op(1)) &&
               GiNaC::ex_to<GiNaC::numeric>(f.op(1)).is_negative()) {
      denominator.push_back({f.op(0), -f.op(1)});
    } else if (GiNaC::is_a<GiNaC::power>(f)) {
      numerator.push_back({f.op(0), f.op(1)});
    } else {
      numerator.push_back({f, 1});
    }
  }
  bool& negative = parts.negative;
  negative = coefficient.is_negative();
  if (negative) coefficient = -coefficient;
  if (coefficient.is_rational() && !coefficient.is_integer()) {
    if (coefficient.numer() != 1) numerator.push_back({coefficient.numer(), 1});
    denominator.push_back({coefficient.denom(), 1});
  } else if (coefficient != 1) {
    numerator.push_back({coefficient, 1});
  }
  if (imaginary_unit) numerator.push_back({GiNaC::I, 1});
  // A sum as a factor with its first term positive, its sign outside: GiNaC keeps
  // -(y_B - y_A)*omega1 or (y_A - y_B)*omega1 as its hash order falls.
  for (std::vector<Factor>* list : {&numerator, &denominator}) {
    for (Factor& f : *list) {
      if (!GiNaC::is_a<GiNaC::add>(f.base) || !GiNaC::is_a<GiNaC::numeric>(f.exponent) ||
          !GiNaC::ex_to<GiNaC::numeric>(f.exponent).is_integer() || !sum_leads_negative(f.base))
        continue;
      f.base = negated_terms(f.base);
      if (GiNaC::ex_to<GiNaC::numeric>(f.exponent).is_odd()) negative = !negative;
    }
  }
  // Differences inside sin, cos and tan: positive term first (the preferred symbol's in
  // the denominator of a solved rate); an odd function's sign comes out.
  const auto orient = [&](std::vector<Factor>& list, const ex* first) {
    for (Factor& f : list) {
      if (!is_trig(f.base) || !GiNaC::is_a<GiNaC::add>(f.base.op(0))) continue;
      if (!leads_negative(f.base.op(0), first)) continue;
      f.flipped = true;
      const bool odd_power = GiNaC::is_a<GiNaC::numeric>(f.exponent) && GiNaC::ex_to<GiNaC::numeric>(f.exponent).is_odd();
      if (is_odd_function(f.base) && odd_power) negative = !negative;
    }
  };
  orient(numerator, nullptr);
  orient(denominator, preferred);
  return parts;
}

std::pair<bool, std::string> TextbookForm::render_product(const ex& e, Context& c) const {
  const ex* preferred = c.preferred;
  c.preferred = nullptr;
  ProductParts parts = product_parts(e, preferred);
  std::vector<Factor>& numerator = parts.numerator;
  std::vector<Factor>& denominator = parts.denominator;
  bool negative = parts.negative;
  // A solved rate: its minus sign into a sine difference of the numerator.
  if (negative && preferred != nullptr) {
    for (Factor& f : numerator) {
      if (is_odd_function(f.base) && GiNaC::is_a<GiNaC::add>(f.base.op(0)) && f.exponent.is_equal(1)) {
        f.flipped = !f.flipped;
        negative = false;
        break;
      }
    }
  }
  // -(A + B)/D reads better as (-A - B)/D.
  if (negative && numerator.size() == 1 && GiNaC::is_a<GiNaC::add>(numerator.front().base) &&
      numerator.front().exponent.is_equal(1) && !denominator.empty()) {
    numerator.front().base = -numerator.front().base;
    negative = false;
  }
  const auto order = [&](std::vector<Factor>& list) {
    std::vector<std::string> texts;  // the last tie-break: the same order from every build
    for (const Factor& f : list) texts.push_back(canonical_text(GiNaC::pow(f.base, f.exponent)));
    std::vector<std::size_t> order(list.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
      const Key ka = key_of(list[i].base), kb = key_of(list[j].base);
      if (ka.rank != kb.rank) return ka.rank < kb.rank;
      if (ka.index != kb.index) return ka.index < kb.index;
      return texts[i] < texts[j];
    });
    std::vector<Factor> sorted;
    for (std::size_t k : order) sorted.push_back(list[k]);
    list = sorted;
  };
  order(numerator);
  order(denominator);
  const auto join = [&](const std::vector<Factor>& list) {
    std::string text;
    for (const Factor& f : list) {
      std::string part;
      if (is_trig(f.base)) {
        // Rendered from the parts: sin of a negated sum would be put back by GiNaC.
        const ex argument = f.flipped ? ex(-f.base.op(0)) : f.base.op(0);
        part = render_function(f.base, argument, c);
        if (!f.exponent.is_equal(1)) {
          const std::string power = render(f.exponent, kPower + 1, c);
          part = c.latex() ? part.substr(0, 4) + "^{" + power + "}" + part.substr(4) : part + "^" + power;
        }
      } else if (f.base.is_equal(GiNaC::I)) {
        part = c.latex() ? "i" : "I";
      } else if (f.exponent.is_equal(1)) {
        // A sum alone over a fraction bar needs no parentheses in LaTeX.
        part = render(f.base, c.latex() && list.size() == 1 && !denominator.empty() ? 0 : kProduct, c);
      } else {
        part = render_power(f.base, f.exponent, c);
      }
      if (!text.empty()) text += c.latex() ? " " : "*";
      text += part;
    }
    return text;
  };
  std::string top = numerator.empty() ? "1" : join(numerator);
  if (denominator.empty()) {
    c.preferred = preferred;
    return {negative, top};
  }
  c.preferred = preferred;
  std::string bottom = join(denominator);
  // A chain's formula: a number's denominator with a sum in the numerator as a factor in
  // front, \frac{1}{2}\cos\alpha\,(...), so that a line can break inside the sum.
  const auto numeric_factor = [](const Factor& f) { return GiNaC::is_a<GiNaC::numeric>(f.base); };
  if (c.latex() && exact_floats_ && std::all_of(denominator.begin(), denominator.end(), numeric_factor) &&
      std::any_of(numerator.begin(), numerator.end(), [](const Factor& f) { return GiNaC::is_a<GiNaC::add>(f.base); })) {
    std::vector<Factor> numbers, rest;
    for (const Factor& f : numerator) (numeric_factor(f) ? numbers : rest).push_back(f);
    return {negative, "\\frac{" + (numbers.empty() ? std::string("1") : join(numbers)) + "}{" + bottom + "}\\," + join(rest)};
  }
  if (c.latex()) return {negative, "\\frac{" + top + "}{" + bottom + "}"};
  // One factor needs no parentheses of its own (a lone sum already has them).
  const bool single = denominator.size() == 1 && denominator.front().exponent.is_equal(1);
  if (numerator.size() == 1 && GiNaC::is_a<GiNaC::add>(numerator.front().base) && numerator.front().exponent.is_equal(1) &&
      top[0] != '(')
    top = "(" + top + ")";
  return {negative, top + "/" + (single ? bottom : "(" + bottom + ")")};
}

std::string TextbookForm::render_power(const ex& base, const ex& exponent, Context& c) const {
  if (exponent.is_equal(GiNaC::numeric(1, 2))) {
    const std::string inner = render(base, 0, c);
    return c.latex() ? "\\sqrt{" + inner + "}" : "sqrt(" + inner + ")";
  }
  const std::string power = render(exponent, kPower + 1, c);
  if (c.latex() && is_trig(base)) {  // \sin^{2}\theta_{3}
    const std::string f = render_function(base, base.op(0), c);
    return f.substr(0, 4) + "^{" + power + "}" + f.substr(4);
  }
  std::string b = render(base, GiNaC::is_a<GiNaC::power>(base) ? 0 : kPower, c);  // wrapped below
  // A prime is a superscript too (x' is x^{\prime}): x'^{2} would be a double superscript.
  if (GiNaC::is_a<GiNaC::power>(base) || (c.latex() && b.find_first_of("^'") != std::string::npos)) b = "(" + b + ")";
  return c.latex() ? b + "^{" + power + "}" : b + "^" + power;
}

std::string TextbookForm::render_argument(const ex& argument, Context& c) const {
  c.argument = true;
  const bool outer = c.bare_numbers;
  c.bare_numbers = true;
  const std::string text = render(argument, 0, c);
  c.argument = false;
  c.bare_numbers = outer;
  return text;
}

std::string TextbookForm::render_function(const ex& f, const ex& argument, Context& c) const {
  const std::string name = GiNaC::ex_to<GiNaC::function>(f).get_name();
  if (!c.latex()) {
    std::string text = name + "(";
    for (std::size_t i = 0; i < f.nops(); ++i) text += (i ? ", " : "") + render_argument(i == 0 ? argument : f.op(i), c);
    return text + ")";
  }
  if (name == "exp") return "e^{" + render_argument(argument, c) + "}";
  if (name == "sin" || name == "cos" || name == "tan") {
    const std::string inner = render_argument(argument, c);
    // \sin\theta_{3}; a number put in for the symbol in parentheses: \sin(30^\circ).
    const bool single = GiNaC::is_a<GiNaC::symbol>(argument) && !(c.texts && c.texts->count(argument));
    // A name starting with a letter (u, or a file's latex = "q") would join the command: \cosu.
    const bool letter = !inner.empty() && std::isalpha(static_cast<unsigned char>(inner[0])) != 0;
    // A number put in for the symbol that comes in its own parentheses (a negative one,
    // "(-12.827^\circ)") is not wrapped again: \cos(-12.827^\circ), not \cos((-12.827^\circ)).
    const bool wrapped = GiNaC::is_a<GiNaC::symbol>(argument) && inner.size() > 2 && inner.front() == '(' &&
                         inner.back() == ')';
    return "\\" + name + (single ? (letter ? " " : "") + inner : wrapped ? inner : "(" + inner + ")");
  }
  std::string text = "\\operatorname{" + name + "}(";
  for (std::size_t i = 0; i < f.nops(); ++i) text += (i ? ", " : "") + render_argument(i == 0 ? argument : f.op(i), c);
  return text + ")";
}

std::string latex_command_name(const std::string& latex, std::size_t backslash, std::size_t& end) {
  end = backslash + 1;
  while (end < latex.size() && std::isalpha(static_cast<unsigned char>(latex[end]))) ++end;
  return latex.substr(backslash + 1, end - backslash - 1);
}

double latex_width(const std::string& text) {
  double width = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '\\') {
      std::size_t end = 0;
      const std::string name = latex_command_name(text, i, end);
      if (name == "sin" || name == "cos" || name == "tan") width += 2.5;
      else if (name == "quad") width += 2;
      else if (name == "qquad") width += 4;
      else if (name.empty()) width += 0.3;  // \, and the like
      else if (name != "frac" && name != "mathit" && name != "mathrm" && name != "text" && name != "bigl" &&
               name != "bigr" && name != "left" && name != "right" && name != "circ" && name != "boxed")
        width += 1;  // a Greek letter, \times, ...
      i = end > i + 1 ? end - 1 : i + 1;
    } else if (ch == '{' || ch == '}' || ch == '^' || ch == '_' || ch == '&') {
    } else if (ch == '+' || ch == '-' || ch == '=') {
      width += 2;  // with the spaces math puts around it
    } else if (ch != ' ') {
      width += 1;
    }
  }
  return width;
}

std::vector<std::string> TextbookForm::latex_lines(const ex& e, const ex& unknown, const SymbolTexts* texts,
                                                   double budget) const {
  const std::string whole = unknown.is_zero() ? (*this)(e, Style::latex, texts) : solved(e, unknown, Style::latex, texts);
  if (latex_width(whole) <= budget) return {whole};
  Context c{Style::latex, texts};
  // A quotient: its numerator's terms over lines after \frac{K}{D}, K the other factors.
  ex sum = e, front = 1, denominator = 1;
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    // The sum over lines: the one of most terms (then the first in canonical order, not
    // in GiNaC's, which differs from build to build).
    std::vector<ex> sums;
    for (std::size_t i = 0; i < e.nops(); ++i) {
      const ex f = e.op(i);
      if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<GiNaC::numeric>(f.op(1)) &&
          GiNaC::ex_to<GiNaC::numeric>(f.op(1)).is_negative()) {
        denominator *= GiNaC::pow(f.op(0), -f.op(1));
      } else if (GiNaC::is_a<GiNaC::add>(f)) {
        sums.push_back(f);
      } else if (GiNaC::is_a<GiNaC::numeric>(f) && GiNaC::ex_to<GiNaC::numeric>(f).is_rational()) {
        // 1/2: its denominator joins the quotient's (\frac{1}{2 BC}, not \frac{\frac{1}{2}}{BC}).
        front *= GiNaC::ex_to<GiNaC::numeric>(f).numer();
        denominator *= GiNaC::ex_to<GiNaC::numeric>(f).denom();
      } else {
        front *= f;
      }
    }
    if (sums.empty()) return {whole};
    const auto chosen = std::min_element(sums.begin(), sums.end(), [this](const ex& a, const ex& b) {
      if (a.nops() != b.nops()) return a.nops() > b.nops();
      return unsigned_text(a) < unsigned_text(b);
    });
    sum = *chosen;
    for (auto it = sums.begin(); it != sums.end(); ++it)
      if (it != chosen) front *= *it;
  } else if (!GiNaC::is_a<GiNaC::add>(e)) {
    return {whole};
  }
  // The signs (of the factor in front, of the denominator and of the sum, each as GiNaC
  // happened to put them) all go into the sum's terms: front and denominator print
  // without a sign, the sum's first term is positive unless the whole is negative.
  bool negative = false;
  if (GiNaC::is_a<GiNaC::add>(sum) && sum_leads_negative(sum)) {
    sum = negated_terms(sum);
    negative = true;
  }
  const auto [front_negative, front_text] = render_product(front, c);
  const bool has_denominator = !denominator.is_equal(1);
  const auto [bottom_negative, bottom] = has_denominator ? render_product(denominator, c) : std::pair<bool, std::string>{};
  if (negative != (front_negative != bottom_negative)) sum = negated_terms(sum);
  std::vector<std::string> lines;
  std::string line;
  // A long denominator goes on lines of its own after the numerator: (...) / (...).
  const bool long_denominator = has_denominator && latex_width(bottom) > budget / 2;
  const bool has_front = front_text != "1";
  if (long_denominator) {
    line = (has_front ? front_text + " " : "") + "\\bigl(";
  } else if (has_denominator || has_front) {
    line = (has_denominator ? "\\frac{" + front_text + "}{" + bottom + "}" : front_text) + "\\bigl(";
  }
  const auto add_terms = [&](const ex& s) {
  std::vector<ex> terms;
  if (GiNaC::is_a<GiNaC::add>(s)) terms.assign(s.begin(), s.end());
  else terms.push_back(s);
  sort_terms(terms, [](const ex&, const ex&) { return 0; });
  bool first = true;
  for (const ex& term : terms) {
    std::string part = render(term, kSum + 1, c);
    if (part.size() > 2 && part[0] == '(' && part[1] == '-' && part.back() == ')') {  // (-x): a sign, not a group
      part = "-" + part.substr(2, part.size() - 3);
    }
    const bool minus = !part.empty() && part[0] == '-';
    if (minus) part = part.substr(1);
    const std::string sign = first ? (minus ? "-" : "") : (minus ? " - " : " + ");
    // A product wider than a line goes over lines factor by factor (the derivatives of
    // nested functions: one product of a line's width many times; TeX stops at a row
    // wider than its largest dimension).
    std::vector<std::string> pieces = {sign + part};
    if (latex_width(part) > kUnbrokenProductLines * budget && GiNaC::is_a<GiNaC::mul>(term))
      pieces = factor_pieces(term, sign, c, budget);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const std::string& piece = pieces[k];
      if ((!first || k > 0) && latex_width(line + piece) > budget) {
        lines.push_back(line);
        line.clear();
      }
      line += piece;
    }
    first = false;
  }
  };
  add_terms(sum);
  if (long_denominator) {
    line += "\\bigr)";
    lines.push_back(line);
    line = "\\bigm/ \\bigl(";
    // The denominator without its sign, multiplied out unless that would give more terms
    // than lines can hold (tan nested 32 deep: a product of 32 sums, 2^32 terms).
    const ex shown = bottom_negative ? -denominator : denominator;
    add_terms(multiplied_out(shown));
    line += "\\bigr)";
  } else if (has_denominator || has_front) {
    line += "\\bigr)";
  }
  lines.push_back(line);
  return lines;
}

// A product's factors as pieces of a line to break between: its sign first (`sign`, the
// minus of a negative coefficient), the coefficient's magnitude, then the other factors in
// canonical order, each as it prints in a product; a factor that is a sum wider than
// `budget` term by term inside its parentheses, the same way.
std::vector<std::string> TextbookForm::factor_pieces(const ex& product, const std::string& sign, Context& c,
                                                     double budget) const {
  std::vector<std::string> pieces;
  std::vector<std::pair<std::string, ex>> factors;
  for (std::size_t i = 0; i < product.nops(); ++i) {
    const ex f = product.op(i);
    if (GiNaC::is_a<GiNaC::numeric>(f) && GiNaC::ex_to<GiNaC::numeric>(f).is_real()) {
      const GiNaC::numeric magnitude = GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(f));
      if (magnitude != 1) pieces.push_back(render(magnitude, kProduct, c));
    } else {
      factors.push_back({canonical_text(f), f});
    }
  }
  std::sort(factors.begin(), factors.end(),
            [](const std::pair<std::string, ex>& a, const std::pair<std::string, ex>& b) { return a.first < b.first; });
  for (const auto& factor : factors) {
    const std::string whole = render(factor.second, kProduct, c);
    if (latex_width(whole) <= kUnbrokenProductLines * budget || !GiNaC::is_a<GiNaC::add>(factor.second)) {
      pieces.push_back(whole);
      continue;
    }
    std::vector<ex> terms(factor.second.begin(), factor.second.end());
    sort_terms(terms, [](const ex&, const ex&) { return 0; });
    for (std::size_t k = 0; k < terms.size(); ++k) {
      std::string part = render(terms[k], kSum + 1, c);
      if (part.size() > 2 && part[0] == '(' && part[1] == '-' && part.back() == ')') part = "-" + part.substr(2, part.size() - 3);
      const bool minus = !part.empty() && part[0] == '-';
      if (minus) part = part.substr(1);
      const std::string term_sign = (k == 0 ? "(" : "") + std::string(k == 0 ? (minus ? "-" : "") : (minus ? "- " : "+ "));
      std::vector<std::string> parts = {term_sign + part};
      if (latex_width(part) > kUnbrokenProductLines * budget && GiNaC::is_a<GiNaC::mul>(terms[k]))
        parts = factor_pieces(terms[k], term_sign, c, budget);
      pieces.insert(pieces.end(), parts.begin(), parts.end());
    }
    pieces.back() += ")";
  }
  for (std::size_t k = 1; k < pieces.size(); ++k) pieces[k] = " " + pieces[k];
  if (pieces.empty()) pieces.push_back("1");
  pieces.front() = sign + pieces.front();
  return pieces;
}

std::string TextbookForm::solved(const ex& e, const ex& unknown, Style style, const SymbolTexts* texts) const {
  Context c{style, texts, &unknown};
  if (GiNaC::is_a<GiNaC::mul>(e) || GiNaC::is_a<GiNaC::power>(e)) {
    const auto [negative, text] = render_product(e, c);
    return negative ? "-" + text : text;
  }
  c.preferred = nullptr;
  return render(e, 0, c);
}

std::string TextbookForm::equation(const ConstraintSystem& system, std::size_t row, Style style) const {
  const Equation& equation = system.equations[row];
  const EquationGroup& group = system.groups[equation.group];
  if (group.vector && group.equations.size() == 2 && (equation.component == "x" || equation.component == "y")) {
    const std::string written = loop_component(group, equation.component == "y", style);
    if (!written.empty()) return written;
  }
  return (*this)(equation.expression, style);
}

std::string TextbookForm::loop_vector(const EquationGroup& group, Style style) const {
  if (group.terms.empty()) return "";
  Context c{style, nullptr};
  std::string text;
  for (const ex& term : group.terms) {
    std::string rendered;
    bool negative = false;
    if (GiNaC::is_a<GiNaC::add>(term)) {  // -(La + I*Lb): a written constant vector
      bool all_negative = true;
      for (std::size_t i = 0; i < term.nops(); ++i) {
        const ex t = term.op(i);
        const ex k = GiNaC::is_a<GiNaC::mul>(t) ? t.op(t.nops() - 1) : t;
        all_negative = all_negative && GiNaC::is_a<GiNaC::numeric>(k) &&
                       (GiNaC::ex_to<GiNaC::numeric>(k).is_real() ? GiNaC::ex_to<GiNaC::numeric>(k).is_negative()
                                                                   : GiNaC::ex_to<GiNaC::numeric>(k).imag().is_negative());
      }
      negative = all_negative && term.nops() > 1;
      rendered = render(negative ? ex(-term) : term, kProduct, c);
    } else {
      rendered = render(term, 0, c);
      negative = !rendered.empty() && rendered[0] == '-';
      if (negative) rendered = rendered.substr(1);
    }
    if (text.empty()) text = negative ? "-" + rendered : rendered;
    else text += (negative ? " - " : " + ") + rendered;
  }
  return text;
}

std::string TextbookForm::loop_component(const EquationGroup& group, bool imaginary, Style style) const {
  if (group.terms.empty()) return "";
  Context c{style, nullptr};
  std::string text;
  for (const ex& term : group.terms) {
    // Each written term's part along x (real) or y (imaginary): length*cos or length*sin
    // of its angle for a link vector, the real or imaginary part of anything else.
    const LinkVector v = split_link_vector(term);
    ex part;
    if (v.polar && complex_parts(v.length).imag.is_zero()) {
      part = v.length * (imaginary ? GiNaC::sin(v.angle) : GiNaC::cos(v.angle));
    } else {
      const ex expanded = term.expand();
      part = imaginary ? imag_part_of(expanded) : real_part_of(expanded);
    }
    if (part.is_zero()) continue;
    std::string rendered = render(part, 0, c);
    bool negative = !rendered.empty() && rendered[0] == '-';
    if (negative) rendered = rendered.substr(1);
    // A sum whose written sign is minus: -(CD + CE)*cos(phi3) reads better than -CD*cos - CE*cos.
    if (text.empty()) text = negative ? "-" + rendered : rendered;
    else text += (negative ? " - " : " + ") + rendered;
  }
  return text.empty() ? "0" : text;
}

}  // namespace kinema
