// The derivation as a LaTeX align* block (amsmath) for pasting into notes.
// Each solved formula is followed by a `% kinema: name = formula` comment in
// GiNaC syntax, so a reader (or a test) can take the formula back exactly.
#include <sstream>

#include <kinema/engine/symbolic/expression_parts.hpp>
#include <kinema/engine/printers/latex/latex_names.hpp>
#include <kinema/engine/printers/printers.hpp>
#include <kinema/engine/symbolic/trig_simplify.hpp>

namespace kinema {
namespace {

using GiNaC::ex;

}  // namespace

std::string latex_vector_loop(const ex& loop, const GiNaC::exmap& names, const std::string& written) {
  // Terms c*exp(I*angle) print as c\,e^{i angle}, as course notes write link vectors,
  // in the order the loop was written when it can be read term by term.
  std::vector<ex> terms;
  if (!written.empty()) {
    GiNaC::symtab table;
    for (const auto& [symbol, latex] : names) table[GiNaC::ex_to<GiNaC::symbol>(symbol).get_name()] = symbol;
    GiNaC::parser reader(table, true);
    try {
      ex sum = 0;
      for (const std::string& t : written_terms(written)) {
        terms.push_back(reader(t));
        sum += terms.back();
      }
      if (!(sum - loop).expand().is_zero()) terms.clear();
    } catch (const std::exception&) {
      terms.clear();
    }
  }
  if (terms.empty()) {
    const ex expanded = loop.expand();
    if (GiNaC::is_a<GiNaC::add>(expanded)) {
      for (const ex& term : expanded) terms.push_back(term);
    } else {
      terms.push_back(expanded);
    }
  }
  std::string text;
  auto term_text = [&](const ex& term) {
    const LinkVector link = split_link_vector(term);
    if (!link.polar) return to_latex(term, names);
    ex coefficient = link.length;
    // -(CD + CE) rather than (-CE - CD): take a common minus sign out of a sum.
    bool negated = false;
    if (GiNaC::is_a<GiNaC::add>(coefficient)) {
      negated = true;
      for (const ex& t : coefficient) {
        const ex factor = GiNaC::is_a<GiNaC::mul>(t) ? t.op(t.nops() - 1) : ex(1);
        negated = negated && GiNaC::is_a<GiNaC::numeric>(factor) && GiNaC::ex_to<GiNaC::numeric>(factor).is_negative();
      }
      if (negated) coefficient = (-coefficient).expand();
    }
    std::string c = to_latex(coefficient, names);
    if (c == "1") c.clear();
    if (c == "-1") c = "-";
    if (GiNaC::is_a<GiNaC::add>(coefficient)) c = "\\left(" + c + "\\right)";
    if (negated) c = "-" + c;
    return c + "\\," + latex_exp(link.angle, names);
  };
  for (const ex& term : terms) {
    const std::string t = term_text(term);
    if (!text.empty() && (t.empty() || t[0] != '-')) text += " + ";
    else if (!text.empty()) text += " ";
    text += t;
  }
  return text;
}

void print_derivation_latex(std::ostream& out, const Mechanism& m, const Derivation& d) {
  const GiNaC::exmap names = latex_symbols(m, d);
  const auto& c = d.closure;
  const std::size_t n = c.unknowns.size();
  const auto column = [&](const std::vector<ex>& entries) { return latex_column(entries, names); };
  std::vector<ex> rates(d.rates.begin(), d.rates.end()), second_rates(d.second_rates.begin(), d.second_rates.end());
  std::vector<ex> velocity_rhs, acceleration_rhs;
  for (std::size_t i = 0; i < n; ++i) {
    velocity_rhs.push_back(-d.input_jacobian(i, 0) * d.input_rate);
    acceleration_rhs.push_back(combine_trig_products(d.acceleration_rhs[i]));
  }
  const std::string jacobian = latex_matrix(d.jacobian, names);

  // Rows of the align* block; a comment may follow a row's text.
  struct Row {
    std::string text, comment;
  };
  std::vector<Row> rows;
  for (std::size_t k = 0; k < m.loops.size(); ++k) {
    const std::string name = latex_escape_text(m.loops[k].name);
    rows.push_back({"\\text{" + name + ":}\\quad & " + latex_vector_loop(c.loop_vectors[k], names, m.loops[k].complex_formula) + " = 0",
                    "loop " + name});
    rows.push_back({"& " + to_latex(c.equations[2 * k], names) + " = 0", ""});
    rows.push_back({"& " + to_latex(c.equations[2 * k + 1], names) + " = 0", ""});
  }
  rows.push_back({"& " + jacobian + column(rates) + " = " + column(velocity_rhs),
                  "velocity: Phi_q qd = -Phi_theta thetad"});
  rows.push_back({"& " + jacobian + column(second_rates) + " = " + column(acceleration_rhs),
                  "acceleration: Phi_q qdd = gamma"});
  for (const auto* solved : {&d.solved_rates, &d.solved_second_rates}) {
    const auto& symbols = solved == &d.solved_rates ? d.rates : d.second_rates;
    for (const RateBlock& block : d.blocks) {
      for (std::size_t j : block.unknowns) {
        rows.push_back({to_latex(symbols[j], names) + " &= " + to_latex((*solved)[j], names),
                        "kinema: " + symbols[j].get_name() + " = " + to_text((*solved)[j])});
      }
    }
  }
  out << "% kinema derive --format latex: " << latex_escape_text(m.title) << "\n";
  out << "% needs \\usepackage{amsmath}\n";
  out << "\\begin{align*}\n";
  for (std::size_t r = 0; r < rows.size(); ++r) {
    out << "  " << rows[r].text << (r + 1 < rows.size() ? " \\\\" : "");
    if (!rows[r].comment.empty()) out << " % " << rows[r].comment;
    out << "\n";
  }
  out << "\\end{align*}\n";
}

}  // namespace kinema
