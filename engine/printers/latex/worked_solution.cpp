// `kinema latex`: a worked solution in LaTeX — data, vector loops, velocity and
// acceleration analysis with the relative and Coriolis terms named, results at
// the requested input values with the numbers put into the solved formulas, a
// TikZ drawing at each (tikz_mechanism.cpp), and pgfplots over the input's
// range (pgfplots.cpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "engine/printers/latex/chain_latex.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/printers/latex/method_latex.hpp"
#include "engine/printers/latex/pgfplots.hpp"
#include "engine/printers/latex/three_methods.hpp"
#include "engine/printers/latex/tikz_chain.hpp"
#include "engine/printers/latex/tikz_instant_centres.hpp"
#include "engine/printers/latex/tikz_mechanism.hpp"
#include "engine/printers/latex/tikz_polygons.hpp"
#include "engine/printers/printer.hpp"
#include "engine/printers/problems/problem_documents.hpp"
#include "engine/analysis/analysis.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/problem_scale.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/base/naming.hpp"
#include "engine/analysis/polygons.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

class DocumentWriter {
 public:
  DocumentWriter(std::ostream& out, const Model& model, const Analysis& analysis)
      : out_(out),
        system_(model.system),
        analysis_(analysis),
        d_(full_derivation(model.derivation)),
        scale_(model.system),
        textbook_(model.system),
        numbers_(model.system) {}

  void preamble() {
    out_ << "\\documentclass[11pt]{article}\n"
         << "\\usepackage[margin=2cm]{geometry}\n"
         << "\\usepackage{amsmath,booktabs}\n"
         << "\\usepackage{tikz}\n\\usetikzlibrary{patterns}\n"
         << (system_.frames.empty() ? "" : "\\usepackage{tikz-3dplot}\n")
         << "\\usepackage{pgfplots}\n\\pgfplotsset{compat=1.16}\n"
         << "\\allowdisplaybreaks\n"
         << "\\begin{document}\n";
  }

  // A chain of frames driven by its joints, worked out at the instant as seed 000 does:
  // the frames, their angular velocities and accelerations, each point's v and a.
  void chain() {
    const ChainAtInstant& chain = *analysis_.chain;
    out_ << "\\subsection*{The chain}\nEach frame turns relative to its parent about the axes of the parent or "
            "its own (right-hand rule); a frame's angular velocity relative to the observer "
         << latex_escape_text(chain.observer)
         << " is the sum of the relative ones along the chain, and a point $P$ at $\\mathbf{r}$ from the origin "
            "of its frame $F$ moves with $\\mathbf{v}_P = \\mathbf{v}_F + \\boldsymbol{\\omega}\\times\\mathbf{r} + "
            "\\mathbf{v}^{\\mathrm{rel}}$ and $\\mathbf{a}_P = \\mathbf{a}_F + \\boldsymbol{\\alpha}\\times\\mathbf{r} + "
            "\\boldsymbol{\\omega}\\times(\\boldsymbol{\\omega}\\times\\mathbf{r}) + 2\\boldsymbol{\\omega}\\times"
            "\\mathbf{v}^{\\mathrm{rel}} + \\mathbf{a}^{\\mathrm{rel}}$. "
         << chain_instant_latex(system_, chain) << ".\n";
    out_ << "\\subsection*{Angular velocities and accelerations}\n\\begin{align*}\n";
    align_rows(chain_frame_rows(chain, textbook_));
    out_ << "\\subsection*{Velocities and accelerations of the points}\n\\begin{align*}\n";
    align_rows(chain_point_rows(chain, textbook_));
  }

  void data() {
    out_ << "\\section*{" << latex_escape_text(system_.title) << "}\n";
    if (!system_.description.empty()) out_ << latex_escape_text(system_.description) << "\n\n";
    statement();
    const Driver& input = system_.input;
    const Dimension kind = input.dimension;
    // One table of what is given: the file's parameters, then the driver's motion.
    out_ << "\\subsection*{Data}\n\\begin{tabular}{ll}\n\\toprule\nparameter & value \\\\\n\\midrule\n";
    for (const SystemParameter& parameter : system_.parameters)
      out_ << "$" << to_latex(parameter.symbol) << "$ & " << given_value(parameter) << " \\\\\n";
    if (kind != Dimension::time) {
      out_ << "\\midrule\n";
      if (!input.values.empty()) out_ << "$" << to_latex(input.symbol) << "$ & $" << driver_values() << "$ \\\\\n";
      out_ << "$" << to_latex(input.rate) << "$ & $" << driver_rate(input.rate_value) << "$ \\\\\n$"
           << to_latex(input.second_rate) << "$ & $" << driver_second_rate() << "$ \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n\\medskip\\noindent "
         << "Input: $" << to_latex(input.symbol) << "$, the "
         << (kind == Dimension::angle ? "crank angle (a negative rate turns it clockwise)"
                                      : kind == Dimension::time ? "time" : "slider position (a negative rate decreases it)");
    out_ << (system_.frames.empty() ? ". Angles are measured counter-clockwise from the $x$ axis."
                                    : ". Angles turn frames by the right-hand rule about their axes.")
         // The digits the numbers below are given to (latex_number's callers: 6, tables of vectors and substitutions 5).
         << " Results to six significant digits (five in tables of vectors and substitutions).\n\n";
    const std::vector<Strokes>& strokes = analysis_.strokes;
    if (analysis_.four_bar || !strokes.empty()) {
      out_ << "\\subsection*{Design figures}\n";
      if (analysis_.four_bar) out_ << "A four-bar: " << four_bar_sentence(*analysis_.four_bar) << ".\n\n";
      for (const Strokes& s : strokes) out_ << "Slider: " << strokes_sentence(s) << ".\n\n";
    }
  }

  void loops() {
    if (system_.frames.empty()) {
      out_ << "\\subsection*{Vector loops}\nEach loop closes ($=0$); its real and imaginary parts are the scalar "
              "equations $\\Phi(q,"
           << to_latex(system_.input.symbol) << ")=0$:\n\\begin{align*}\n";
    } else {  // a closed spatial chain: a distance between two of its points is a link's length
      out_ << "\\subsection*{Closure of the spatial chain}\nThe chain closes where the distance between the ends of each "
              "closing link equals the link's length; that distance closure, $\\Phi(q,"
           << to_latex(system_.input.symbol) << ")=0$, written with the points' coordinates:\n\\begin{align*}\n";
    }
    std::vector<std::string> rows;
    for (const EquationGroup& group : system_.groups) {
      // A group without link vectors (a distance closure) names its first equation instead.
      const std::string loop = latex_vector_loop(group);
      std::string label = "\\text{" + latex_escape_text(group.name) + ":}\\quad ";
      if (!loop.empty()) {
        rows.push_back(label + "& " + loop + " = 0");
        label.clear();
      }
      for (std::size_t row : group.equations) {
        const std::string written = textbook_.equation(system_, row, TextbookForm::Style::latex);
        // Numbered by the equation's row of Phi, so that the text can say "from (1) and (2)".
        const std::string tag = " \\tag{" + std::to_string(row + 1) + "}";
        if (latex_width(written) <= kLatexLineBudget) {
          rows.push_back(label + "& " + written + " = 0" + tag);
        } else {  // a long closure: over lines
          const auto lines = textbook_.latex_lines(system_.equations[row].expression, 0, nullptr, kLatexLineBudget);
          for (std::size_t k = 0; k < lines.size(); ++k)
            rows.push_back((k == 0 ? label + "& " : "&\\quad ") + lines[k] + (k + 1 == lines.size() ? " = 0" + tag : ""));
        }
        label.clear();
      }
    }
    align_rows(rows);
  }

  // Phi_q times a column of rates equal to a column: as matrices when they fit the page,
  // else row by row, each side over lines.
  void matrix_equation(std::vector<std::string>& rows, const std::vector<ex>& rates, const std::vector<ex>& rhs,
                       const std::string& rhs_matrix) const {
    // As printed: each matrix column as wide as its widest entry.
    const auto widest = [&](const std::vector<ex>& column) {
      double w = 0;
      for (const ex& e : column) w = std::max(w, latex_width(textbook_(e, TextbookForm::Style::latex)));
      return w + 2;
    };
    double width = widest(rates) + widest(rhs);
    for (unsigned j = 0; j < d_.jacobian.cols(); ++j) {
      std::vector<ex> column;
      for (unsigned i = 0; i < d_.jacobian.rows(); ++i) column.push_back(d_.jacobian(i, j));
      width += widest(column);
    }
    if (width <= kLatexLineBudget + 6) {
      rows.push_back("& " + latex_matrix(d_.jacobian, textbook_) + latex_column(rates) + " = " + rhs_matrix);
      return;
    }
    for (std::size_t i = 0; i < rates.size(); ++i) {
      ex left = 0;
      for (std::size_t j = 0; j < rates.size(); ++j) left += d_.jacobian(i, j) * rates[j];
      const auto lhs = textbook_.latex_lines(left, 0, nullptr, kLatexLineBudget);
      const auto right = textbook_.latex_lines(rhs[i], 0, nullptr, kLatexLineBudget);
      const std::string label = "\\text{(" + std::to_string(i + 1) + ")}\\quad & ";
      if (lhs.size() == 1 && right.size() == 1 && latex_width(lhs[0] + right[0]) + 2 <= kLatexLineBudget) {
        rows.push_back(label + lhs[0] + " = " + right[0]);
        continue;
      }
      for (std::size_t k = 0; k < lhs.size(); ++k)
        rows.push_back((k == 0 ? "\\text{(" + std::to_string(i + 1) + ")}\\quad & " : "&\\quad ") + lhs[k]);
      for (std::size_t k = 0; k < right.size(); ++k) rows.push_back((k == 0 ? "&= " : "&\\quad ") + right[k]);
    }
  }

  void velocity() {
    const Driver& input = system_.input;
    out_ << "\\subsection*{Velocity analysis}\nDifferentiating the loop equations " << equation_range()
         << " in time gives the velocity "
            "equations $\\Phi_q\\,\\dot q = -\\Phi_{"
         << to_latex(input.symbol) << "}\\," << to_latex(input.rate) << "$:\n\\begin{align*}\n";
    std::vector<ex> rates, rhs;
    for (std::size_t i = 0; i < system_.unknowns.size(); ++i) {
      rates.push_back(system_.unknowns[i].rate);
      rhs.push_back(-d_.input_jacobian(i, 0) * input.rate);
    }
    std::vector<std::string> rows;
    matrix_equation(rows, rates, rhs, latex_column(rhs, textbook_));
    solved_rows(rows, 1);
    align_rows(rows);
  }

  void acceleration() {
    out_ << "\\subsection*{Acceleration analysis}\nDifferentiating " << equation_range() << " once more: $\\Phi_q\\,\\ddot q = \\gamma$ with "
            "the same matrix $\\Phi_q$:\n\\begin{align*}\n";
    std::vector<ex> second;
    for (const Coordinate& q : system_.unknowns) second.push_back(q.second_rate);
    std::string gamma = "\\begin{bmatrix}";
    for (std::size_t i = 0; i < second.size(); ++i) gamma += (i ? " \\\\ " : " ") + std::string("\\gamma_{") + std::to_string(i + 1) + "}";
    gamma += " \\end{bmatrix}";
    std::vector<std::string> rows;
    std::vector<ex> gammas;
    for (std::size_t i = 0; i < second.size(); ++i) gammas.push_back(GiNaC::symbol("\\gamma_{" + std::to_string(i + 1) + "}"));
    matrix_equation(rows, second, gammas, gamma);
    // The right-hand side one row at a time: a column of it would not fit the page.
    for (std::size_t i = 0; i < d_.acceleration_rhs_combined.size(); ++i)
      for (const LatexRow& row :
           latex_broken_rows("\\gamma_{" + std::to_string(i + 1) + "}",
                             textbook_.latex_lines(d_.acceleration_rhs_combined[i], 0, nullptr, kLatexLineBudget)))
        rows.push_back(row.text);
    solved_rows(rows, 2);
    align_rows(rows);
    sliding_link_terms();
  }

  // The velocity and acceleration analysis group by group, as the seeds work it out.
  void by_method() {
    const DyadDerivation& derivation = *analysis_.dyads;
    const DerivationMethod method = derivation.method;
    for (const bool acceleration : {false, true}) {
      out_ << "\\subsection*{" << (acceleration ? "Acceleration" : "Velocity") << " analysis by "
           << method_title(method) << "}\n"
           << (method == DerivationMethod::relative_velocity
                   ? (acceleration ? "Each dyad's middle joint from both sides, with $-\\omega^2\\mathbf{r}$ and, "
                                     "where a joint slides on a turning link, the Coriolis term $2\\boldsymbol{\\omega}"
                                     "\\times\\mathbf{v}^r$; the components solved for the dyad's two unknowns.\n"
                                   : "Each dyad's middle joint from both sides; the components solved for the dyad's "
                                     "two unknowns.\n")
                   : (acceleration ? "The velocity relations differentiated once more, solved for the middle "
                                     "joint's acceleration; then each link's $\\alpha$.\n"
                                   : "Each dyad's middle joint on a circle about a pin or on a guide line, "
                                     "differentiated in time and solved for its velocity; then each link's "
                                     "$\\omega$.\n"))
           << "\\begin{align*}\n";
      std::vector<std::string> rows;
      for (const MethodStep& step : derivation.steps) {
        for (const LatexRow& row : method_rows(step, acceleration, textbook_))
          rows.push_back(row.comment.empty() ? row.text : row.text + " %% " + row.comment);
      }
      align_rows(rows);
    }
  }

  // Value `row` of the printed values, with what the analysis drew and found there.
  void results(const MotionTable& table, std::size_t index, const ValueAnalysis& at) {
    const MotionState s = table[index];
    // The row as the table prints it, each value at its scale (RowScales): the tables below
    // show round-off beside their columns and at the problem's size as 0.
    const std::vector<ResultColumn> columns = result_columns(system_, scale_, table.is_circuit());
    row_.assign(columns.size(), 0.0);
    result_values(system_, scale_, table, index, row_.data());
    with_ = RowScales(system_, columns)(row_.data());
    const Driver& input = system_.input;
    const Dimension kind = input.dimension;
    out_ << kLatexPartBreak << "\\subsection*{Results at $" << to_latex(input.symbol) << " = "
         << numbers_(scale_.input(s.input), kind, 0) << coordinate_unit(kind) << "$}\n";
    if (s.status != Status::ok) {
      out_ << latex_escape_text(describe_failure(system_, s)) << "\n\n";
      if (s.status == Status::unassembled) return;
    }
    out_ << "\\begin{tabular}{lrrr}\n\\toprule\ncoordinate & value & rate & second rate \\\\\n\\midrule\n";
    for (std::size_t j = 0; j < system_.unknowns.size(); ++j) {
      const Coordinate& q = system_.unknowns[j];
      const Dimension k = q.dimension;
      const std::size_t v = kInputColumns + 3 * j;
      out_ << "$" << to_latex(q.symbol) << "$ & $" << shown(v, k, 0, 6) << coordinate_unit(k) << "$ & ";
      if (s.status == Status::ok) {
        // The answers boxed, as a worked solution marks them.
        out_ << "$" << to_latex(q.rate) << " = \\boxed{" << shown(v + 1, k, 1, 6) << "}\\,\\mathrm{"
             << scale_.rate_unit(k) << "}$ & $" << to_latex(q.second_rate) << " = \\boxed{"
             << shown(v + 2, k, 2, 6) << "}\\,\\mathrm{" << scale_.second_rate_unit(k) << "}$";
      } else {
        out_ << "undefined & undefined";
      }
      out_ << " \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n";
    if (!system_.frames.empty()) {  // a spatial chain: 3-D points, the frames, a 3-D sketch
      if (s.status == Status::ok) spatial_tables();
      if (s.status == Status::ok && !is_driven_chain(system_)) substitution(s);
      write_tikz_chain(out_, system_, at.frames, s);
      return;
    }
    if (s.status == Status::ok && !system_.points.empty()) point_table();
    if (s.status == Status::ok && system_.plan) linkage_table();
    if (s.status == Status::ok) substitution(s);
    write_tikz_mechanism(out_, system_, at, analysis_.link_labels, s);
    const auto& polygons = at.polygons;
    if (polygons) {
      out_ << kLatexPartBreak << "\\subsubsection*{Velocity and acceleration polygons}\nEach link vector's velocity, chained from the "
              "pole $o$ in the order the loops and points are written: a turning link's relative velocity "
              "$\\omega r$ across it, a sliding point's velocity along its line; accelerations in the parts "
              "normal ($\\omega^{2} r$, towards the link's start), tangential ($\\alpha r$), Coriolis "
              "($2\\omega v^{r}$) and relative (along the line).";
      // Each sliding point's image on its turning line, named from the polygon (A' under A
      // in the crank-shaper, B' under B elsewhere).
      const auto math_name = [](const std::string& name) {
        std::string escaped;
        for (char c : name) escaped += c == '_' ? std::string("\\_") : std::string(1, c);
        return "$" + (name.find('_') == std::string::npos ? name : "\\mathit{" + escaped + "}") + "$";
      };
      for (const PolygonVertex& v : polygons->first.vertices)
        if (!v.name.empty() && v.name.back() == '\'') {
          const std::string sliding = v.name.substr(0, v.name.size() - 1);
          out_ << " " << math_name(v.name) << " is the point of a turning line under the point " << math_name(sliding)
               << " that slides along it.";
        }
      out_ << "\n\n";
      write_tikz_polygon(out_, system_, textbook_, polygons->first);
      write_tikz_polygon(out_, system_, textbook_, polygons->second);
    }
    if (const auto& centres = at.centres) {
      out_ << kLatexPartBreak << "\\subsubsection*{Instant centres}\n";
      write_tikz_instant_centres(out_, system_, at, *centres);
      if (polygons) write_three_methods(out_, system_, three_methods(system_, polygons->first, *centres), *centres);
    }
  }

  void plots(const MotionTable& sweep) { write_pgfplots(out_, system_, sweep); }

  void end() { out_ << "\\end{document}\n"; }

 private:
  std::ostream& out_;
  const ConstraintSystem& system_;
  const Analysis& analysis_;
  const Derivation& d_;
  OutputScale scale_;
  TextbookForm textbook_;
  DocumentNumbers numbers_;
  // The current value's row as the table prints it and each value's scale (results).
  std::vector<double> row_, with_;

  // Value k of the current row at its scale, in `digits` (the tables of vectors: 5).
  std::string shown(std::size_t k, Dimension dimension, int order, int digits = 5) const {
    return numbers_(row_[k], dimension, order, digits, with_[k]);
  }

  // The loop equations' numbers as the text cites them: "(1)", "(1) and (2)", "(1)--(4)".
  std::string equation_range() const {
    const std::size_t n = system_.equations.size();
    if (n <= 1) return "(1)";
    return "(1)" + std::string(n == 2 ? " and " : "--") + "(" + std::to_string(n) + ")";
  }

  // "Given ... Find ...", from the file: the mechanism, its driver's motion and what kinema
  // solves (the unknowns, their rates and second rates, the points' motion).
  void statement() {
    const Driver& input = system_.input;
    const Dimension kind = input.dimension;
    const auto list = [](const std::vector<std::string>& items) {
      std::string text;
      for (std::size_t k = 0; k < items.size(); ++k)
        text += (k == 0 ? "" : k + 1 == items.size() ? (items.size() > 2 ? ", and " : " and ") : ", ") + items[k];
      return text;
    };
    out_ << "\\textbf{Given:} " << (system_.frames.empty() ? "the mechanism" : "the chain") << " ``"
         << latex_escape_text(system_.title) << "'' with the data below";
    if (kind == Dimension::time) {
      out_ << ", its joints moving in time as the file gives them";
      if (!input.values.empty()) out_ << ", at $" << to_latex(input.symbol) << " = " << driver_values() << "$";
    } else {
      out_ << ", driven by $" << to_latex(input.symbol) << "$";
      if (!input.values.empty()) out_ << " at $" << to_latex(input.symbol) << " = " << driver_values() << "$";
      out_ << " with $" << to_latex(input.rate) << " = " << driver_rate(input.rate_value) << "$ and $"
           << to_latex(input.second_rate) << " = " << driver_second_rate() << "$";
    }
    std::vector<std::string> found, rates, second_rates, points;
    for (const Coordinate& q : system_.unknowns) {
      found.push_back("$" + to_latex(q.symbol) + "$");
      rates.push_back("$" + to_latex(q.rate) + "$");
      second_rates.push_back("$" + to_latex(q.second_rate) + "$");
    }
    for (const PointObservable& p : system_.points) points.push_back(latex_escape_text(p.name));
    std::vector<std::string> asked;
    if (!found.empty())
      asked.push_back(list(found) + ", " + (found.size() > 1 ? "their rates " : "its rate ") + list(rates) + " and " +
                      (found.size() > 1 ? "second rates " : "second rate ") + list(second_rates));
    if (!points.empty())
      asked.push_back("the velocity and acceleration of " + std::string(points.size() > 1 ? "points " : "point ") + list(points));
    if (!system_.frames.empty()) asked.push_back("each frame's angular velocity and acceleration");
    out_ << ". \\textbf{Find:} ";
    for (std::size_t k = 0; k < asked.size(); ++k) out_ << (k ? "; " : "") << asked[k];
    out_ << ".\n\n";
  }

  // The driver's values from the file in the document's units (the first few of a sweep).
  std::string driver_values() const {
    const Driver& input = system_.input;
    std::string text;
    for (std::size_t k = 0; k < input.values.size() && k < 4; ++k)
      text += (k ? ",\\ " : "") + numbers_(scale_.input(input.values[k]), input.dimension, 0) + coordinate_unit(input.dimension);
    if (input.values.size() > 4) text += ",\\ \\ldots";
    return text;
  }

  // The design figures typeset (describe_four_bar and describe_strokes write them for a
  // terminal: "phi = 0.0000 deg (-0.0344774 m)").
  std::string degrees(double deg) const { return numbers_(deg, Dimension::angle, 0) + "^{\\circ}"; }

  std::string four_bar_sentence(const FourBarFigures& f) const {
    const std::string input = to_latex(system_.input.symbol);
    // "s + l = 40 + 120 = 160 < p + q = 180 (mm)": the relation in math, its unit after it.
    std::string relation = f.inequality, unit;
    const auto open = relation.rfind(" (");
    if (open != std::string::npos && relation.back() == ')') {
      unit = relation.substr(open + 2, relation.size() - open - 3);
      relation = relation.substr(0, open);
    }
    std::string text = (f.grashof == "change point" || f.grashof.rfind("non-", 0) == 0 ? "" : "Grashof ") +
                       latex_escape_text(f.grashof) + " ($" + relation +
                       (unit.empty() ? "" : "\\,\\mathrm{" + latex_escape_text(unit) + "}") + "$)";
    if (std::isfinite(f.least_transmission)) {
      text += "; transmission angle from $" + degrees(f.least_transmission) + "$ ($" + input + " = " + degrees(f.least_at) +
              "$) to $" + degrees(f.greatest_transmission) + "$ ($" + input + " = " + degrees(f.greatest_at) + "$)" +
              (f.full_turn ? "" : " where it can be assembled");
    }
    if (f.toggles.empty()) return text + "; no toggle position";
    text += "; toggle positions at $" + input + " = ";
    for (std::size_t k = 0; k < f.toggles.size(); ++k) text += (k ? ",\\ " : "") + degrees(f.toggles[k]);
    return text + "$";
  }

  std::string strokes_sentence(const Strokes& s) const {
    std::string name = latex_escape_text(s.name);
    for (const Coordinate& q : system_.unknowns)
      if (q.name == s.name) name = to_latex(q.symbol);
    const auto length = [&](double v) {
      return numbers_(v, Dimension::length, 0) + "\\,\\mathrm{" + latex_escape_text(scale_.length_unit) + "}";
    };
    const std::string input = to_latex(system_.input.symbol);
    if (s.two_limits()) {
      return "$" + name + "$ at its limits at $" + input + " = " + degrees(s.limit_inputs[0]) + "$ ($" +
             length(s.limit_values[0]) + "$) and $" + degrees(s.limit_inputs[1]) + "$ ($" + length(s.limit_values[1]) +
             "$); strokes of $" + degrees(s.strokes[0]) + "$ and $" + degrees(s.strokes[1]) + "$ of crank, time ratio $" +
             latex_number(s.time_ratio) + "$";
    }
    // As describe_strokes words it: each limit a maximum or a minimum, the strokes between.
    const std::size_t n = s.limit_inputs.size();
    const auto separator = [n](std::size_t k) { return k == 0 ? " " : k + 1 == n ? " and " : ", "; };
    std::string text = "$" + name + "$ at " + std::to_string(n) + (n == 1 ? " limit position" : " limit positions") + " at";
    for (std::size_t k = 0; k < n; ++k)
      text += std::string(separator(k)) + "$" + input + " = " + degrees(s.limit_inputs[k]) + "$ (" +
              (s.maxima[k] ? "maximum" : "minimum") + " $" + length(s.limit_values[k]) + "$)";
    if (!s.whole_turn) return text + "; no strokes: part of the turn does not assemble";
    if (s.strokes.empty()) return text;
    text += "; strokes of";
    for (std::size_t k = 0; k < n; ++k) text += std::string(separator(k)) + "$" + degrees(s.strokes[k]) + "$";
    return text + " of crank, each from a limit to the next";
  }

  // After a coordinate's value: the degree sign, or its unit.
  std::string coordinate_unit(Dimension dimension) const {
    const std::string unit = scale_.coordinate_unit(dimension);
    return unit == "deg" ? "^{\\circ}" : "\\,\\mathrm{" + latex_escape_text(unit) + "}";
  }

  // A given value in the document's units ("60\\,mm", "35.5377^\\circ"), round-off as 0.
  std::string in_document_units(double si, Dimension dimension) const {
    if (dimension == Dimension::length)
      return numbers_(si / scale_.length, dimension, 0) + "\\,\\mathrm{" + latex_escape_text(scale_.length_unit) + "}";
    if (dimension == Dimension::angle) return numbers_(to_degrees(si), dimension, 0) + "^{\\circ}";
    return latex_number(si);
  }

  // A parameter as the file gave it: its text, typeset, where a person wrote it ("60 mm",
  // "0.3 m", "30 deg"); a value the front end worked out (a joint's offset, kept as
  // 0.059999999999999998 m to read back exactly) in the document's units and digits; a
  // formula with its value.
  std::string given_value(const SystemParameter& p) const {
    if (p.formula) return "$" + to_latex(*p.formula) + " = " + in_document_units(p.value, p.dimension) + "$";
    // A chain's rates at the instant (omega1_0, written without unit): the rate's unit.
    std::vector<const Coordinate*> coordinates = {&system_.input};
    for (const Coordinate& q : system_.unknowns) coordinates.push_back(&q);
    for (const Coordinate* q : coordinates) {
      if (p.dimension != Dimension::number || q->dimension == Dimension::time) continue;
      const std::string name = p.symbol.get_name();
      if (name == q->rate.get_name() + "_0")
        return "$" + numbers_(scale_.rate(q->dimension, p.value), q->dimension, 1) + "\\,\\mathrm{" + scale_.rate_unit(q->dimension) + "}$";
      if (name == q->second_rate.get_name() + "_0")
        return "$" + numbers_(scale_.rate(q->dimension, p.value), q->dimension, 2) + "\\,\\mathrm{" +
               scale_.second_rate_unit(q->dimension) + "}$";
    }
    const std::string& text = p.text;
    std::size_t end = 0;
    while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) || std::string("+-.eE").find(text[end]) != std::string::npos))
      ++end;
    std::size_t digits = 0;  // significant digits of the number written
    bool leading = true;
    for (std::size_t i = 0; i < end && std::toupper(static_cast<unsigned char>(text[i])) != 'E'; ++i) {
      if (!std::isdigit(static_cast<unsigned char>(text[i]))) continue;
      leading = leading && text[i] == '0';
      if (!leading) ++digits;
    }
    if (end == 0) return latex_escape_text(text);  // not a number first: as written
    if (digits > 12) return "$" + in_document_units(p.value, p.dimension) + "$";  // a machine's representation
    std::string number = text.substr(0, end);
    const auto e = number.find_first_of("eE");
    if (e != std::string::npos) number = number.substr(0, e) + "\\cdot 10^{" + std::to_string(std::atoi(number.c_str() + e + 1)) + "}";
    std::size_t u = end;
    while (u < text.size() && text[u] == ' ') ++u;
    const std::string unit = text.substr(u);
    // A length or angle written without unit (a chain's value at the instant, in SI): in the document's.
    if (unit.empty()) return "$" + (p.dimension == Dimension::number ? number : in_document_units(p.value, p.dimension)) + "$";
    if (unit == "deg") return "$" + number + "^{\\circ}$";
    const bool plain = std::all_of(unit.begin(), unit.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '/' || c == '^'; });
    return plain ? "$" + number + "\\,\\mathrm{" + unit + "}$" : "$" + number + "$ " + latex_escape_text(unit);
  }

  // The driver's rate as the document states it: as the file wrote it ("60 rpm",
  // "90 deg/s") and its value in the document's unit (= 6.283 rad/s); once where the file
  // wrote it in that unit.
  std::string driver_rate(double si) const {
    const Dimension kind = system_.input.dimension;
    return as_written(system_.input.rate_text, scale_.rate(kind, si), kind, 1, scale_.rate_unit(kind));
  }

  std::string driver_second_rate() const {
    const Dimension kind = system_.input.dimension;
    return as_written(system_.input.second_rate_text, scale_.rate(kind, system_.input.second_rate_value), kind, 2,
                      scale_.second_rate_unit(kind));
  }

  // A rate in math mode: `text` as written (a number and a unit), then " = " its value
  // `shown` in the document's `unit`; that value alone where the text is missing, is in
  // that unit, or is not a plain number and unit.
  std::string as_written(const std::string& text, double shown, Dimension kind, int order, const std::string& unit) const {
    const std::string in_units = numbers_(shown, kind, order) + "\\,\\mathrm{" + unit + "}";
    std::size_t end = 0;
    while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) || std::string("+-.eE").find(text[end]) != std::string::npos))
      ++end;
    std::size_t u = end;
    while (u < text.size() && text[u] == ' ') ++u;
    const std::string written_unit = text.substr(u);
    const bool plain = end > 0 && !written_unit.empty() &&
                       std::all_of(written_unit.begin(), written_unit.end(), [](char c) {
                         return std::isalnum(static_cast<unsigned char>(c)) || c == '/' || c == '^';
                       });
    if (!plain || written_unit == unit) return in_units;
    std::string number = text.substr(0, end);
    if (number.front() == '+') number = number.substr(1);
    const auto e = number.find_first_of("eE");
    if (e != std::string::npos) number = number.substr(0, e) + "\\cdot 10^{" + std::to_string(std::atoi(number.c_str() + e + 1)) + "}";
    const std::string value = numbers_(shown, kind, order, 4);
    return number + "\\,\\mathrm{" + written_unit + "} = " + value + "\\,\\mathrm{" + unit + "}";
  }

  // The solved rates (order 1) or second rates (order 2), block by block, each with
  // a "% kinema: name = formula" comment in GiNaC syntax for reading it back.
  void solved_rows(std::vector<std::string>& rows, int order) const {
    for (const SolvingBlock& block : d_.blocks) {
      for (std::size_t j : block.unknowns) {
        const GiNaC::realsymbol& symbol = order == 1 ? system_.unknowns[j].rate : system_.unknowns[j].second_rate;
        const ex& formula = order == 1 ? d_.solved_rates[j] : d_.solved_second_rates[j];
        const auto lines = textbook_.latex_lines(formula, system_.unknowns[j].symbol, nullptr, kLatexLineBudget);
        for (const LatexRow& row :
             latex_broken_rows(to_latex(symbol), lines, "", "kinema: " + symbol.get_name() + " = " +
                                   textbook_.solved(formula, system_.unknowns[j].symbol, TextbookForm::Style::text)))
          rows.push_back(row.comment.empty() ? row.text : row.text + " %% " + row.comment);
      }
    }
  }

  // Joints and links: slider blocks turning with their guides, and at each slider the
  // relative velocity and acceleration along its line and the Coriolis acceleration.
  void linkage_table() {
    std::size_t v = linkage_columns_begin(system_);  // the row's joints-and-links values
    const std::string l = scale_.length_unit;
    const auto blocks = block_links(system_);
    if (!blocks.empty()) {
      out_ << "\\medskip\n\\begin{tabular}{lrrr}\n\\toprule\nslider block & angle & $\\omega$ & $\\alpha$ \\\\\n"
              " & $^{\\circ}$ & $\\mathrm{rad/s}$ & $\\mathrm{rad/s^2}$ \\\\\n\\midrule\n";
      for (const auto& block : blocks) {
        out_ << latex_escape_text(system_.plan->links[block.first - 1].name) << " & $"
             << shown(v, Dimension::angle, 0) << "$ & $" << shown(v + 1, Dimension::angle, 1) << "$ & $"
             << shown(v + 2, Dimension::angle, 2) << "$ \\\\\n";
        v += 3;
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
    if (system_.plan->sliders.empty()) return;  // no slider: no table of empty rows
    const auto pair = [&](std::size_t c, int order) {
      return "$(" + shown(c, Dimension::length, order) + ",\\ " + shown(c + 1, Dimension::length, order) + ")$";
    };
    out_ << "\\medskip\n\\begin{tabular}{lccc}\n\\toprule\nslider & relative velocity $\\mathbf{v}^r$ & relative "
            "acceleration $\\mathbf{a}^r$ & Coriolis $2\\boldsymbol{\\omega}\\times\\mathbf{v}^r$ \\\\\n & $\\mathrm{"
         << l << "/s}$ & $\\mathrm{" << l << "/s^2}$ & $\\mathrm{" << l << "/s^2}$ \\\\\n\\midrule\n";
    for (const SolvingPlan::Slider& slider : system_.plan->sliders) {
      out_ << latex_escape_text(system_.plan->joints[slider.joint].name) << " & " << pair(v, 1) << " & " << pair(v + 2, 2)
           << " & " << pair(v + 4, 2) << " \\\\\n";
      v += 6;
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n";
    // The guide's point under each slider on a moving guide (the seed's v_B1), and each
    // block's turning relative to a link it is pinned to (omega23).
    const auto guides = guide_points(system_);
    if (!guides.empty()) {
      out_ << "\\medskip\n\\begin{tabular}{llcc}\n\\toprule\npoint & on link & velocity $\\mathbf{v}$ & acceleration "
              "$\\mathbf{a}$ \\\\\n & & $\\mathrm{"
           << l << "/s}$ & $\\mathrm{" << l << "/s^2}$ \\\\\n\\midrule\n";
      for (const GuidePoint& g : guides) {
        const SolvingPlan::Slider& slider = system_.plan->sliders[g.slider];
        // B on link 3 is B_3, as the seed writes it (braced: the point's name may carry a subscript).
        const std::string& link = system_.plan->links[slider.guide - 1].name;
        out_ << "${" << latex_symbol_name(system_.points[g.point].name) << "}_{\\mathrm{" << latex_escape_text(link)
             << "}}$ & " << latex_escape_text(link)
             << " & " << pair(v, 1) << " & " << pair(v + 2, 2) << " \\\\\n";
        v += 4;
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
    const auto turnings = relative_turnings(system_);
    if (!turnings.empty()) {
      out_ << "\\medskip\n\\begin{tabular}{llrr}\n\\toprule\nlinks & at & relative $\\omega$ & relative $\\alpha$ "
              "\\\\\n & & $\\mathrm{rad/s}$ & $\\mathrm{rad/s^2}$ \\\\\n\\midrule\n";
      for (const RelativeTurning& r : turnings) {
        out_ << latex_escape_text(system_.plan->links[r.block - 1].name) << ", "
             << latex_escape_text(system_.plan->links[r.other - 1].name) << " & "
             << latex_escape_text(system_.plan->joints[r.joint].name) << " & $" << latex_symbol_name(r.rate_name)
             << " = " << shown(v, Dimension::angle, 1) << "$ & $" << latex_symbol_name(r.second_rate_name)
             << " = " << shown(v + 1, Dimension::angle, 2) << "$ \\\\\n";
        v += 2;
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
  }

  // Spatial chains: each point's position, velocity and acceleration as vectors, and
  // each frame's angular velocity and acceleration (observer basis).
  void spatial_tables() {
    const std::string l = latex_escape_text(scale_.length_unit);
    const auto triple = [&](std::size_t v, Dimension dimension, int order) {
      return "$(" + shown(v, dimension, order) + ",\\ " + shown(v + 1, dimension, order) + ",\\ " +
             shown(v + 2, dimension, order) + ")$";
    };
    // A point's three vectors as columns: three triples in a row were wider than the text
    // (45 pt past it for robot_arm_slider at t = 0.67 s), and a column's width is one number's.
    const auto column = [&](std::size_t v, int order) {
      return "\\begin{pmatrix} " + shown(v, Dimension::length, order) + " \\\\ " + shown(v + 1, Dimension::length, order) +
             " \\\\ " + shown(v + 2, Dimension::length, order) + " \\end{pmatrix}";
    };
    std::size_t v = kInputColumns + 3 * system_.unknowns.size();  // the row's points, then its frames
    if (!system_.points.empty()) {
      out_ << "\\medskip\n\\begin{tabular}{lccc}\n\\toprule\npoint & position ($\\mathrm{" << l
           << "}$) & velocity ($\\mathrm{" << l << "/s}$) & acceleration ($\\mathrm{" << l
           << "/s^2}$) \\\\\n\\midrule\n";
      for (std::size_t p = 0; p < system_.points.size(); ++p) {
        const std::size_t d = system_.points[p].components.size();  // position, velocity, speed, acceleration, magnitude
        // The velocity and acceleration are the point's answers: boxed.
        out_ << (p ? "\\addlinespace\n" : "") << latex_escape_text(system_.points[p].name) << " & $" << column(v, 0)
             << "$ & $\\boxed{" << column(v + d, 1) << "}$ & $\\boxed{" << column(v + 2 * d + 1, 2) << "}$ \\\\\n";
        v += 3 * d + 2;
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
    out_ << "\\medskip\n\\begin{tabular}{lcc}\n\\toprule\nframe & $\\boldsymbol{\\omega}$ relative to "
         << latex_escape_text(chain_observer(system_)) << " ($\\mathrm{rad/s}$) & $\\boldsymbol{\\alpha}$ "
         << "($\\mathrm{rad/s^2}$) \\\\\n\\midrule\n";
    for (std::size_t f = 0; f < system_.frames.size(); ++f, v += 6) {
      out_ << latex_escape_text(system_.frames[f].name) << " & " << triple(v, Dimension::angle, 1) << " & "
           << triple(v + 3, Dimension::angle, 2) << " \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n";
  }

  void point_table() {
    // Planar points (the drawing and the table's columns are 2-D).
    const std::string l = scale_.length_unit;
    // Nine columns, two of them boxed: closer than the default 6 pt, so that six-character
    // numbers in every column (Example 4.2 at phi = 165 deg was 12 pt too wide) fit the text width.
    out_ << "\\medskip\n{\\setlength{\\tabcolsep}{4pt}\\begin{tabular}{lrrrrrrrr}\n\\toprule\npoint & $x$ & $y$ & $v_x$ & $v_y$ & $|v|$ & $a_x$ & "
            "$a_y$ & $|a|$ \\\\\n & \\multicolumn{2}{c}{$\\mathrm{"
         << l << "}$} & \\multicolumn{3}{c}{$\\mathrm{" << l << "/s}$} & \\multicolumn{3}{c}{$\\mathrm{" << l
         << "/s^2}$} \\\\\n\\midrule\n";
    std::size_t v = kInputColumns + 3 * system_.unknowns.size();
    for (std::size_t p = 0; p < system_.points.size(); ++p, v += 8) {
      out_ << latex_escape_text(system_.points[p].name);
      static constexpr int order[8] = {0, 0, 1, 1, 1, 2, 2, 2};  // x, y, v_x, v_y, |v|, a_x, a_y, |a|: the row's order
      for (int k = 0; k < 8; ++k) {
        const std::string number = shown(v + k, Dimension::length, order[k]);
        // The point's speed and acceleration are its answers: boxed.
        out_ << " & $" << (k == 4 || k == 7 ? "\\boxed{" + number + "}" : number) << "$";
      }
      out_ << " \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}}\n\n";
  }

  // The solved formulas with the numbers put in, as a worked solution shows them:
  // lengths in the output unit, angles in degrees, rates as computed. Every number of a
  // line in one unit, so that the line evaluates to the value it states: where the
  // formulas carry lengths as numbers (a spatial chain's offsets, in metres), lengths
  // are put in in metres too.
  void substitution(const MotionState& s) {
    const bool in_metres = formulas_carry_numbers();
    const double unit = in_metres ? 1.0 : scale_.length;  // metres per substituted length unit
    const std::string unit_name = in_metres ? "m" : scale_.length_unit;
    // Braced, so that a suffix (the degree sign) never follows another superscript
    // (a number in powers of ten: 10^{-15}).
    auto shown = [](const std::string& number, const std::string& suffix) {
      const bool power = !suffix.empty() && number.find('^') != std::string::npos;
      return "(" + (power ? "{" + number + "}" : number) + suffix + ")";
    };
    // An SI value of `dimension` differentiated `order` times, round-off as 0 (DocumentNumbers).
    auto quantity = [&](Dimension dimension, int order, double si) {
      if (dimension == Dimension::angle && order == 0) return shown(numbers_(to_degrees(si), dimension, 0, 5), "^{\\circ}");
      if (dimension == Dimension::length)
        return shown(latex_number(numbers_.cleaned(si / scale_.length, dimension, order) * scale_.length / unit, 5), "");
      return shown(numbers_(dimension == Dimension::number ? si : scale_.rate(dimension, si), dimension, order, 5), "");
    };
    TextbookForm::SymbolTexts numbers;
    for (const SystemParameter& parameter : system_.parameters)
      numbers[parameter.symbol] = quantity(parameter.dimension, 0, parameter.value);
    const Driver& input = system_.input;
    numbers[input.symbol] = quantity(input.dimension, 0, s.input);
    numbers[input.rate] = quantity(input.dimension, 1, s.input_rate);
    numbers[input.second_rate] = quantity(input.dimension, 2, s.input_second_rate);
    for (std::size_t j = 0; j < system_.unknowns.size(); ++j) {
      const Coordinate& q = system_.unknowns[j];
      numbers[q.symbol] = quantity(q.dimension, 0, s.q[j]);
      numbers[q.rate] = quantity(q.dimension, 1, s.qd[j]);
      numbers[q.second_rate] = quantity(q.dimension, 2, s.qdd[j]);
    }
    out_ << "Numeric substitution (lengths in " << latex_escape_text(unit_name)
         << (in_metres && unit_name != scale_.length_unit ? ", the unit of the lengths the formulas carry as numbers" : "")
         << "):\n\\begin{align*}\n";
    std::vector<std::string> rows;
    for (int order = 1; order <= 2; ++order) {
      for (const SolvingBlock& block : d_.blocks) {
        for (std::size_t j : block.unknowns) {
          const Coordinate& q = system_.unknowns[j];
          const double si = order == 1 ? s.qd[j] : s.qdd[j];
          const bool length = q.dimension == Dimension::length;
          const std::string value = length ? latex_number(numbers_.cleaned(si / scale_.length, q.dimension, order) * scale_.length / unit)
                                           : numbers_(scale_.rate(q.dimension, si), q.dimension, order);
          const std::string result_unit = length ? unit_name + (order == 1 ? "/s" : "/s^2")
                                                 : order == 1 ? scale_.rate_unit(q.dimension) : scale_.second_rate_unit(q.dimension);
          const ex& formula = order == 1 ? d_.solved_rates[j] : d_.solved_second_rates[j];
          const auto lines = textbook_.latex_lines(formula, q.symbol, &numbers, kLatexLineBudget);
          const std::string result = " = " + value + "\\,\\mathrm{" + result_unit + "}";
          for (const LatexRow& row : latex_broken_rows(to_latex(order == 1 ? q.rate : q.second_rate), lines, result))
            rows.push_back(row.text);
        }
      }
    }
    align_rows(rows);
  }

  // Whether a solved formula has a number that is not a plain fraction: a length the
  // front end put in as a number (in metres).
  bool formulas_carry_numbers() const {
    for (const auto* formulas : {&d_.solved_rates, &d_.solved_second_rates})
      for (const ex& formula : *formulas)
        for (auto it = formula.preorder_begin(); it != formula.preorder_end(); ++it)
          if (GiNaC::is_a<GiNaC::numeric>(*it) && !GiNaC::ex_to<GiNaC::numeric>(*it).is_rational()) return true;
    return false;
  }

  void align_rows(const std::vector<LatexRow>& rows) {
    std::vector<std::string> texts;
    for (const LatexRow& row : rows) texts.push_back(row.comment.empty() ? row.text : row.text + " %% " + row.comment);
    align_rows(texts);
  }

  // Rows of an align*; text after " %% " in a row becomes a comment after the row's end.
  void align_rows(const std::vector<std::string>& rows) {
    std::vector<LatexRow> split;
    for (const std::string& row : rows) {
      const auto comment = row.find(" %% ");
      split.push_back({row.substr(0, comment), comment == std::string::npos ? "" : row.substr(comment + 4)});
    }
    out_ << latex_align_rows(split) << "\\end{align*}\n";
  }

  // Points sliding along turning links: the acceleration's named terms (derived
  // once, in the symbolic stage).
  void sliding_link_terms() {
    // Each term as one product, its sign combined with the coefficient's
    // (2 * -(CB' w3) prints as -2 CB' w3, -(-CB w3^2) as CB w3^2).
    const auto term = [](const ex& coefficient, const std::string& direction) {
      const std::string c = to_latex(coefficient);
      if (c == "0") return std::string("0");
      const std::string factor = GiNaC::is_a<GiNaC::add>(coefficient) ? "(" + c + ")" : c == "1" ? "" : c == "-1" ? "-" : c;
      return factor + "\\," + direction;
    };
    for (const SlidingLinkTerms& t : d_.sliding_links) {
      const std::string e = latex_exp(t.angle);
      out_ << "In loop " << latex_escape_text(system_.groups[t.group].name) << ", the point at the end of $"
           << to_latex(t.length) << "\\," << e
           << "$ slides along a turning link: its acceleration has the relative term $" << term(t.relative, e)
           << "$ along the link, the Coriolis term $" << term(2 * t.coriolis, "i\\," + e)
           << "$, and the terms of the link's own rotation, $" << term(t.tangential, "i\\," + e) << "$ and $"
           << term(-t.normal, e) << "$.\n\n";
    }
  }
};

class WorkedSolutionPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::document; }
  const char* name() const override { return "latex"; }

  ViewNeeds needs(const PrintJob& job) const override {
    ViewNeeds needs = derivation_needs(job, !is_driven_chain(job.model.system));
    needs.design_figures = true;
    needs.drawings = true;
    return needs;
  }

  void print(std::ostream& out, const PrintJob& job) const override {
    const Analysis& analysis = analysis_of(job);
    DocumentWriter writer(out, job.model, analysis);
    if (!job.fragment) writer.preamble();
    writer.data();
    // A key leads with its answers (a grader looks for them first), then works them out.
    if (job.answers) out << problem_answers_latex(job.model.system, *job.answers);
    if (is_driven_chain(job.model.system)) {  // worked out at the instant, as seed 000
      writer.chain();
    } else if (job.method == DerivationMethod::loops) {
      writer.loops();
      writer.velocity();
      writer.acceleration();
    } else {
      writer.loops();
      writer.by_method();
    }
    if (job.values) {
      if (analysis.values.size() != job.values->size())
        throw std::logic_error("a document was given no analysis of its values: build it with analyse_for_views");
      for (std::size_t row = 0; row < job.values->size(); ++row) writer.results(*job.values, row, analysis.values[row]);
    }
    if (job.sweep) writer.plots(*job.sweep);
    if (!job.fragment) writer.end();
  }
};

}  // namespace

const Printer& worked_solution_printer() {
  static const WorkedSolutionPrinter printer;
  return printer;
}

}  // namespace kinema
