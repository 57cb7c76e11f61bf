// The derivation as a LaTeX align* block (amsmath) for pasting into notes.
// Each solved formula is followed by a `% kinema: name = formula` comment in
// GiNaC syntax, so a reader (or a test) can take the formula back exactly.
#include <kinema/engine/printers/latex/chain_latex.hpp>
#include <kinema/engine/printers/latex/latex_format.hpp>
#include <kinema/engine/printers/latex/method_latex.hpp>
#include <kinema/engine/printers/printer.hpp>
#include <kinema/engine/report/structure.hpp>

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
    // A distance closure (a spatial chain) has no link vectors: its name labels its first equation.
    const std::string loop = latex_vector_loop(group);
    std::string label = "\\text{" + name + ":}\\quad ", comment = group.kind + " " + name;
    if (!loop.empty()) {
      rows.push_back({label + "& " + loop + " = 0", comment});
      label.clear();
      comment.clear();
    }
    for (std::size_t row : group.equations) {
      rows.push_back({label + "& " + textbook.equation(system, row, latex) + " = 0", comment});
      label.clear();
      comment.clear();
    }
  }
  rows.push_back({"& " + jacobian + latex_column(rates) + " = " + latex_column(velocity_rhs, textbook),
                  "velocity: Phi_q qd = -Phi_theta thetad"});
  rows.push_back({"& " + jacobian + latex_column(second_rates) + " = " + latex_column(d.acceleration_rhs_combined, textbook),
                  "acceleration: Phi_q qdd = gamma"});
  for (int order = 1; order <= 2; ++order) {
    for (const SolvingBlock& block : d.blocks) {
      for (std::size_t j : block.unknowns) {
        const GiNaC::realsymbol& symbol = order == 1 ? system.unknowns[j].rate : system.unknowns[j].second_rate;
        const ex& solved = order == 1 ? d.solved_rates[j] : d.solved_second_rates[j];
        const auto lines = textbook.latex_lines(solved, system.unknowns[j].symbol, nullptr, kLatexLineBudget);
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

    std::vector<LatexRow> rows;
    if (system.linkage) {  // joints and links: the solving order the loops come from
      // Gruebler's count typeset (mobility_text writes it for a terminal: "3*5 - 2*7").
      const int n = system.linkage->body_count, j = system.linkage->joint_count;
      rows.push_back({"\\text{structure:}\\quad & \\text{mobility } 3(n - 1) - 2j = 3\\cdot " + std::to_string(n - 1) +
                          " - 2\\cdot " + std::to_string(j) + " = " + std::to_string(3 * (n - 1) - 2 * j) + "\\quad\\text{($n = " +
                          std::to_string(n) + "$ bodies with ground, $j = " + std::to_string(j) + "$ joints)}",
                      "structure"});
      for (const std::string& line : structure_lines(*system.linkage))
        rows.push_back({"& \\text{" + latex_escape_text(line) + "}", ""});
    }
    if (job.method != DerivationMethod::loops) {  // the seeds' methods, group by group
      const DyadDerivation derivation = derive_by_dyads(system, job.method);
      for (const bool acceleration : {false, true}) {
        rows.push_back({"\\text{" + std::string(acceleration ? "accelerations" : "velocities") + " by " +
                            method_title(job.method) + ":}\\quad",
                        std::string(acceleration ? "acceleration" : "velocity") + ": " + method_name(job.method)});
        for (const MethodStep& step : derivation.steps)
          for (const LatexRow& row : method_rows(step, acceleration, textbook)) rows.push_back(row);
      }
    }
    if (is_driven_chain(system)) {  // a chain of frames worked out at the instant, as seed 000
      const ChainAtInstant chain = chain_at_instant(system, job.basis);
      rows.push_back({"&\\text{" + chain_instant_latex(system, chain) + "}", "spatial chain"});
      for (const auto& part : {chain_frame_rows(chain, textbook), chain_point_rows(chain, textbook)}) rows.insert(rows.end(), part.begin(), part.end());
    } else if (job.method == DerivationMethod::loops) {
      loop_rows(rows, system, d, jacobian, rates, second_rates, velocity_rhs, textbook);
    }
    out << "% kinema derive --format latex: " << latex_escape_text(system.title) << "\n";
    out << "% needs \\usepackage{amsmath}\n";
    out << "\\begin{align*}\n";
    for (std::size_t r = 0; r < rows.size(); ++r) {
      out << "  " << rows[r].text << (r + 1 < rows.size() ? " \\\\" : "");
      if (!rows[r].comment.empty()) out << " % " << rows[r].comment;
      out << "\n";
    }
    out << "\\end{align*}\n";
  }
};

}  // namespace

const Printer& derivation_latex_printer() {
  static const DerivationLatexPrinter printer;
  return printer;
}

}  // namespace kinema
