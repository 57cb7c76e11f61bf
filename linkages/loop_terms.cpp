#include "linkages/loop_terms.hpp"

namespace kinema::linkage_detail {
namespace {

using GiNaC::ex;

std::string shown(const Operand& operand) { return operand.formula ? "(" + operand.text + ")" : operand.text; }

std::string term_text(const Term& term) {
  std::string text = term.times_i ? "I*" + shown(term.factor) : shown(term.factor);
  if (term.angle.empty()) return text;
  std::string argument;
  for (const Operand& operand : term.angle) argument += (argument.empty() ? "" : " + ") + shown(operand);
  return text + "*exp(I*" + (argument.find(' ') != std::string::npos ? "(" + argument + ")" : argument) + ")";
}

ex operand_expression(const Operand& operand, FormulaReader& formulas, const std::string& context) {
  if (!operand.formula) {
    if (const ex* symbol = formulas.defined(operand.text)) return *symbol;
  }
  return formulas.read(operand.text, context);  // what the file wrote (or a name it does not define: its message)
}

// GiNaC keeps sums and products in a canonical order: built so, a term is the same
// expression as its text read.
ex term_expression(const Term& term, FormulaReader& formulas, const std::string& context) {
  ex e = operand_expression(term.factor, formulas, context);
  if (!term.angle.empty()) {
    ex argument = 0;
    for (const Operand& operand : term.angle) argument += operand_expression(operand, formulas, context);
    e = e * GiNaC::exp(GiNaC::I * argument);
  }
  if (term.times_i) e = GiNaC::I * e;
  return term.negative ? -e : e;
}

}  // namespace

std::vector<Term> negated(std::vector<Term> terms) {
  for (Term& t : terms) t.negative = !t.negative;
  return terms;
}

std::string sum_text(const std::vector<Term>& terms) {
  if (terms.empty()) return "0";
  std::string text;
  for (const Term& t : terms) {
    if (text.empty()) text = t.negative ? "-" + term_text(t) : term_text(t);
    else text += (t.negative ? " - " : " + ") + term_text(t);
  }
  return text;
}

PlanarVector planar_vector(const TermSum& sum, FormulaReader& formulas, const std::string& kind) {
  const std::string context = sum.where.str() + ": " + kind + " \"" + sum.name + "\"";
  PlanarVector v{sum.name, sum.where, 0, {}, "", sum.is_joint};
  for (const Term& term : sum.terms) {
    v.terms.push_back(term_expression(term, formulas, context));
    v.vector += v.terms.back();
  }
  if (v.terms.empty()) v.terms.push_back(0);  // as "0" reads: one term
  return v;
}

}  // namespace kinema::linkage_detail
