// The derivation as a LaTeX align* block (amsmath) for pasting into notes.
// Each solved formula is followed by a `% kinema: name = formula` comment in
// GiNaC syntax, so a reader (or a test) can take the formula back exactly.
#include <algorithm>

#include "engine/printers/latex/chain_latex.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/latex/method_latex.hpp"
#include "engine/printers/printer.hpp"
#include "engine/analysis/structure.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

// The loops' equations, the velocity and acceleration equations in matrix form, and
// the solved rates.
void loop_rows(std::vector<LatexRow>& rows, const ConstraintSystem& system, const Derivation& d, const std::string& jacobian,
               const std::vector<ex>& rates, const std::vector<ex>& second_rates, const std::vector<ex>& velocity_rhs,
               const TextbookForm& textbook) {
  constexpr auto latex = TextbookForm::Style::latex;
  for (const EquationGroup& group : system.groups) {
    const std::string name = latex_escape_text(group.name);
    // A closure that is no sum of vectors (a spatial one) starts at its first equation.
    const std::string vectors = latex_vector_loop(group);
    std::string label = "\\text{" + name + ":}\\quad ", comment = group.kind + " " + name;
    if (!vectors.empty()) {
      rows.push_back({label + "& " + vectors + " = 0", comment});
      label.clear();
      comment.clear();
    }
    for (std::size_t row : group.equations) {
      const std::string written = textbook.equation(system, row, latex);
      // A long closure (a quotient cannot be broken as written): its terms over lines.
      const std::vector<std::string> lines =
          latex_width(written) <= kPlainArticleBudget
              ? std::vector<std::string>{written}
              : textbook.latex_lines(system.equations[row].expression, 0, nullptr, kPlainArticleBudget);
      for (std::size_t k = 0; k < lines.size(); ++k)
        rows.push_back({(k == 0 ? label + "& " : "&\\quad ") + lines[k] + (k + 1 == lines.size() ? " = 0" : ""),
                        k == 0 ? comment : ""});
      label.clear();
      comment.clear();
    }
  }
  // Phi_q times the rates = the right side: as matrices when they fit, else row by row
  // (each row's sides then broken over lines by latex_fit_rows).
  const auto widest = [&](const std::vector<ex>& column) {
    double w = 0;
    for (const ex& e : column) w = std::max(w, latex_width(textbook(e, latex)));
    return w + 2;
  };
  double matrix_width = 0;
  for (unsigned j = 0; j < d.jacobian.cols(); ++j) {
    std::vector<ex> column;
    for (unsigned i = 0; i < d.jacobian.rows(); ++i) column.push_back(d.jacobian(i, j));
    matrix_width += widest(column);
  }
  bool entries_written = false;
  const auto matrix_equation = [&](const std::vector<ex>& unknown_rates, const std::vector<ex>& rhs, const std::string& comment) {
    if (matrix_width + widest(unknown_rates) + widest(rhs) <= kPlainArticleBudget) {
      rows.push_back({"& " + jacobian + latex_column(unknown_rates) + " = " + latex_column(rhs, textbook), comment});
      return;
    }
    // Too wide: the entries of Phi_q one by one (once), then each row with them; every
    // formula over lines.
    const auto entry = [](std::size_t i, std::size_t j) {
      return "(\\Phi_{q})_{" + std::to_string(i + 1) + std::to_string(j + 1) + "}";
    };
    if (!entries_written) {
      for (std::size_t i = 0; i < rhs.size(); ++i)
        for (std::size_t j = 0; j < unknown_rates.size(); ++j)
          if (!d.jacobian(i, j).is_zero())
            for (const LatexRow& row : latex_broken_rows(entry(i, j), textbook.latex_lines(d.jacobian(i, j), 0, nullptr, kPlainArticleBudget)))
              rows.push_back(row);
      entries_written = true;
    }
    for (std::size_t i = 0; i < rhs.size(); ++i) {
      std::string left;
      for (std::size_t j = 0; j < unknown_rates.size(); ++j)
        if (!d.jacobian(i, j).is_zero()) left += (left.empty() ? "" : " + ") + entry(i, j) + "\\," + textbook(unknown_rates[j], latex);
      const auto lines = textbook.latex_lines(rhs[i], 0, nullptr, kPlainArticleBudget);
      rows.push_back({"& " + (left.empty() ? "0" : left) + " = " + lines.front(), i == 0 ? comment : ""});
      for (std::size_t k = 1; k < lines.size(); ++k) rows.push_back({"&\\quad " + lines[k], ""});
    }
  };
  matrix_equation(rates, velocity_rhs, "velocity: Phi_q qd = -Phi_theta thetad");
  matrix_equation(second_rates, d.acceleration_rhs_combined, "acceleration: Phi_q qdd = gamma");
  for (int order = 1; order <= 2; ++order) {
    for (const SolvingBlock& block : d.blocks) {
      for (std::size_t j : block.unknowns) {
        const GiNaC::realsymbol& symbol = order == 1 ? system.unknowns[j].rate : system.unknowns[j].second_rate;
        const ex& solved = order == 1 ? d.solved_rates[j] : d.solved_second_rates[j];
        const auto lines = textbook.latex_lines(solved, system.unknowns[j].symbol, nullptr, kPlainArticleBudget);
        for (const LatexRow& row :
             latex_broken_rows(to_latex(symbol), lines, "", "kinema: " + symbol.get_name() + " = " +
                                   textbook.solved(solved, system.unknowns[j].symbol, TextbookForm::Style::text)))
          rows.push_back(row);
      }
    }
  }
}

class DerivationLatexPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::derivation; }
  const char* name() const override { return "latex"; }
  ViewNeeds needs(const PrintJob& job) const override { return derivation_needs(job, true); }

  void print(std::ostream& out, const PrintJob& job) const override {
    const ConstraintSystem& system = job.model.system;
    const Derivation& d = full_derivation(job.model.derivation);
    const std::size_t n = system.unknowns.size();
    std::vector<ex> rates, second_rates, velocity_rhs;
    for (const Coordinate& q : system.unknowns) {
      rates.push_back(q.rate);
      second_rates.push_back(q.second_rate);
    }
    for (std::size_t i = 0; i < n; ++i) velocity_rhs.push_back(-d.input_jacobian(i, 0) * system.input.rate);
    const TextbookForm textbook(system);
    const std::string jacobian = latex_matrix(d.jacobian, textbook);

    // Several align* blocks, each free to break across pages (\allowdisplaybreaks in a
    // group), every row within a plain article's text width (kPlainArticleBudget).
    out << "% kinema derive --format latex: " << latex_escape_text(system.title) << "\n";
    out << "% needs \\usepackage{amsmath}\n";
    out << "\\begingroup\\allowdisplaybreaks\n";
    const auto block = [&](const std::vector<LatexRow>& rows) {
      if (rows.empty()) return;
      out << "\\begin{align*}\n" << latex_align_rows(latex_fit_rows(rows, kPlainArticleBudget)) << "\\end{align*}\n";
    };
    if (system.linkage) {  // joints and links: the solving order the loops come from
      // Gruebler's count typeset (mobility_text writes it for a terminal: "3*5 - 2*7").
      const int n = system.linkage->body_count, j = system.linkage->joint_count;
      out << "% structure\n\\noindent structure: mobility $3(n - 1) - 2j = 3\\cdot " << n - 1 << " - 2\\cdot " << j
          << " = " << 3 * (n - 1) - 2 * j << "$ ($n = " << n << "$ bodies with ground, $j = " << j << "$ joints)";
      for (const std::string& line : structure_lines(*system.linkage)) out << "\\\\\n" << latex_escape_text(line);
      out << "\\par\n";
    }
    if (job.method != DerivationMethod::loops) {  // the seeds' methods, group by group
      const DyadDerivation& derivation = *analysis_of(job).dyads;
      for (const bool acceleration : {false, true}) {
        std::vector<LatexRow> rows = {latex_intertext(std::string(acceleration ? "Accelerations" : "Velocities") + " by " +
                                                          method_title(job.method) + ":",
                                                      std::string(acceleration ? "acceleration" : "velocity") + ": " +
                                                          method_name(job.method))};
        for (const MethodStep& step : derivation.steps)
          for (const LatexRow& row : method_rows(step, acceleration, textbook, kPlainArticleBudget)) rows.push_back(row);
        block(rows);
      }
    }
    if (is_driven_chain(system)) {  // a chain of frames worked out at the instant, as seed 000
      const ChainAtInstant& chain = *analysis_of(job).chain;
      out << "% spatial chain\n\\noindent " << chain_instant_latex(system, chain) << ".\n";
      block(chain_frame_rows(chain, textbook, kPlainArticleBudget));
      block(chain_point_rows(chain, textbook, kPlainArticleBudget));
    } else if (job.method == DerivationMethod::loops) {
      std::vector<LatexRow> rows;
      loop_rows(rows, system, d, jacobian, rates, second_rates, velocity_rhs, textbook);
      block(rows);
    }
    out << "\\endgroup\n";
  }
};

}  // namespace

const Printer& derivation_latex_printer() {
  static const DerivationLatexPrinter printer;
  return printer;
}

}  // namespace kinema
