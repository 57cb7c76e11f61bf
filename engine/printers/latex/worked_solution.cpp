// `kinema latex`: a worked solution in LaTeX — data, vector loops, velocity and
// acceleration analysis with the relative and Coriolis terms named, results at
// the requested input values with the numbers put into the solved formulas, a
// TikZ drawing at each (tikz_mechanism.cpp), and pgfplots over the input's
// range (pgfplots.cpp).
#include <algorithm>
#include <cmath>

#include <kinema/engine/printers/latex/chain_latex.hpp>
#include <kinema/engine/printers/latex/latex_format.hpp>
#include <kinema/engine/printers/latex/method_latex.hpp>
#include <kinema/engine/printers/latex/pgfplots.hpp>
#include <kinema/engine/printers/latex/three_methods.hpp>
#include <kinema/engine/printers/latex/tikz_chain.hpp>
#include <kinema/engine/printers/latex/tikz_instant_centres.hpp>
#include <kinema/engine/printers/latex/tikz_mechanism.hpp>
#include <kinema/engine/printers/latex/tikz_polygons.hpp>
#include <kinema/engine/printers/printer.hpp>
#include <kinema/engine/report/design_figures.hpp>
#include <kinema/engine/report/diagnostics.hpp>
#include <kinema/engine/report/geometry.hpp>
#include <kinema/engine/report/instant_centres.hpp>
#include <kinema/engine/report/output_scale.hpp>
#include <kinema/engine/report/polygons.hpp>
#include <kinema/engine/symbolic/expression_parts.hpp>
#include <kinema/engine/symbolic/naming.hpp>

namespace kinema {
namespace {

using GiNaC::ex;

class DocumentWriter {
 public:
  DocumentWriter(std::ostream& out, const Model& model)
      : out_(out),
        model_(model),
        system_(model.system),
        d_(full_derivation(model.derivation)),
        scale_(model.system),
        geometry_(model.system),
        polygons_(model.system),
        textbook_(model.system),
        four_bar_(four_bar_figures(model)) {}

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
  void chain(const std::string& basis) {
    const ChainAtInstant chain = chain_at_instant(system_, basis);
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
    out_ << "\\subsection*{Data}\n\\begin{tabular}{ll}\n\\toprule\nparameter & value \\\\\n\\midrule\n";
    for (const SystemParameter& parameter : system_.parameters) {
      out_ << "$" << to_latex(parameter.symbol) << "$ & ";
      if (!parameter.formula) {
        out_ << latex_escape_text(parameter.text);
      } else {
        out_ << "$" << to_latex(*parameter.formula) << " = " << latex_number(parameter.value) << "$";
      }
      out_ << " \\\\\n";
    }
    const Driver& input = system_.input;
    const Dimension kind = input.dimension;
    out_ << "\\bottomrule\n\\end{tabular}\n\n"
         << "Input: $" << to_latex(input.symbol) << "$ (" << (kind == Dimension::angle ? "crank angle" : kind == Dimension::time ? "time" : "slider position")
         << "), $" << to_latex(input.rate) << " = " << latex_number(scale_.rate(kind, input.rate_value))
         << "\\,\\mathrm{" << scale_.rate_unit(kind) << "}$ (negative: "
         << (kind == Dimension::angle ? "clockwise" : "decreasing") << "), $" << to_latex(input.second_rate) << " = "
         << latex_number(scale_.rate(kind, input.second_rate_value)) << "\\,\\mathrm{"
         << scale_.second_rate_unit(kind) << "}$. Unknowns: ";
    for (std::size_t j = 0; j < system_.unknowns.size(); ++j)
      out_ << (j ? ", " : "") << "$" << to_latex(system_.unknowns[j].symbol) << "$";
    out_ << (system_.frames.empty() ? ". Angles are measured counter-clockwise from the $x$ axis.\n\n"
                                    : ". Angles turn frames by the right-hand rule about their axes.\n\n");
    const std::vector<Strokes> strokes = slider_strokes(model_);
    if (four_bar_ || !strokes.empty()) {
      out_ << "\\subsection*{Design figures}\n";
      if (four_bar_) out_ << "A four-bar: " << latex_escape_text(describe_four_bar(*four_bar_, system_.input.name)) << ".\n\n";
      for (const Strokes& s : strokes)
        out_ << "Slider: " << latex_escape_text(describe_strokes(s, system_.input.name, scale_.length_unit)) << ".\n\n";
    }
  }

  void loops() {
    out_ << "\\subsection*{Vector loops}\nEach loop closes ($=0$); its real and imaginary parts are the scalar "
            "equations $\\Phi(q,"
         << to_latex(system_.input.symbol) << ")=0$:\n\\begin{align*}\n";
    std::vector<std::string> rows;
    for (const EquationGroup& group : system_.groups) {
      rows.push_back("\\text{" + latex_escape_text(group.name) + ":}\\quad & " + latex_vector_loop(group) + " = 0");
      for (std::size_t row : group.equations) {
        const std::string written = textbook_.equation(system_, row, TextbookForm::Style::latex);
        if (latex_width(written) <= kLatexLineBudget) {
          rows.push_back("& " + written + " = 0");
        } else {  // a long closure: over lines
          const auto lines = textbook_.latex_lines(system_.equations[row].expression, 0, nullptr, kLatexLineBudget);
          for (std::size_t k = 0; k < lines.size(); ++k)
            rows.push_back((k == 0 ? "& " : "&\\quad ") + lines[k] + (k + 1 == lines.size() ? " = 0" : ""));
        }
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
    out_ << "\\subsection*{Velocity analysis}\nDifferentiating the loop equations in time gives the velocity "
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
    out_ << "\\subsection*{Acceleration analysis}\nDifferentiating once more: $\\Phi_q\\,\\ddot q = \\gamma$ with "
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
  void by_method(DerivationMethod method) {
    const DyadDerivation derivation = derive_by_dyads(system_, method);
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

  void results(const MotionState& s) {
    const Driver& input = system_.input;
    const Dimension kind = input.dimension;
    out_ << "\\clearpage\n\\subsection*{Results at $" << to_latex(input.symbol) << " = "
         << latex_number(scale_.input(s.input)) << "\\,\\mathrm{" << scale_.coordinate_unit(kind) << "}$}\n";
    if (s.status != Status::ok) {
      out_ << latex_escape_text(describe_failure(system_, s)) << "\n\n";
      if (s.status == Status::unassembled) return;
    }
    out_ << "\\begin{tabular}{lrrr}\n\\toprule\ncoordinate & value & rate & second rate \\\\\n\\midrule\n";
    for (std::size_t j = 0; j < system_.unknowns.size(); ++j) {
      const Coordinate& q = system_.unknowns[j];
      const Dimension k = q.dimension;
      out_ << "$" << to_latex(q.symbol) << "$ & $" << latex_number(scale_.coordinate(k, s.q[j])) << "\\,\\mathrm{"
           << scale_.coordinate_unit(k) << "}$ & ";
      if (s.status == Status::ok) {
        out_ << "$" << to_latex(q.rate) << " = " << latex_number(scale_.rate(k, s.qd[j])) << "\\,\\mathrm{"
             << scale_.rate_unit(k) << "}$ & $" << to_latex(q.second_rate) << " = "
             << latex_number(scale_.rate(k, s.qdd[j])) << "\\,\\mathrm{" << scale_.second_rate_unit(k) << "}$";
      } else {
        out_ << "undefined & undefined";
      }
      out_ << " \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n";
    if (!system_.frames.empty()) {  // a spatial chain: 3-D points, the frames, a 3-D sketch
      if (s.status == Status::ok) spatial_tables(s);
      if (s.status == Status::ok && !is_driven_chain(system_)) substitution(s);
      write_tikz_chain(out_, system_, s);
      return;
    }
    if (s.status == Status::ok && !system_.points.empty()) point_table(s);
    if (s.status == Status::ok && system_.linkage) linkage_table(s);
    if (s.status == Status::ok) substitution(s);
    write_tikz_mechanism(out_, system_, geometry_, s);
    const auto polygons = polygons_.polygons(s);
    if (polygons) {
      out_ << "\\clearpage\n\\subsubsection*{Velocity and acceleration polygons}\nEach link vector's velocity, chained from the "
              "pole $o$ in the order the loops and points are written: a turning link's relative velocity "
              "$\\omega r$ across it, a sliding point's velocity along its line; accelerations in the parts "
              "normal ($\\omega^{2} r$, towards the link's start), tangential ($\\alpha r$), Coriolis "
              "($2\\omega v^{r}$) and relative (along the line).";
      for (const PolygonVertex& v : polygons->first.vertices)
        if (v.name.back() == '\'') {
          out_ << " $B'$ is the point of a turning line under the point $B$ that slides along it.";
          break;
        }
      out_ << "\n\n";
      write_tikz_polygon(out_, system_, textbook_, polygons->first);
      write_tikz_polygon(out_, system_, textbook_, polygons->second);
    }
    if (const auto centres = instant_centres(system_, s)) {
      out_ << "\\clearpage\n\\subsubsection*{Instant centres}\n";
      write_tikz_instant_centres(out_, system_, geometry_, s, *centres);
      if (polygons) write_three_methods(out_, system_, three_methods(system_, polygons->first, *centres), *centres);
    }
  }

  void plots(const MotionTable& sweep) { write_pgfplots(out_, system_, sweep); }

  void end() { out_ << "\\end{document}\n"; }

 private:
  std::ostream& out_;
  const Model& model_;
  const ConstraintSystem& system_;
  const Derivation& d_;
  OutputScale scale_;
  MechanismGeometry geometry_;
  PolygonBuilder polygons_;
  TextbookForm textbook_;
  std::optional<FourBarFigures> four_bar_;

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
  void linkage_table(const MotionState& s) {
    std::vector<double> values(result_columns(system_, scale_).size() - linkage_columns_begin(system_));
    linkage_values(system_, scale_, s, values.data());
    const double* v = values.data();
    const std::string l = scale_.length_unit;
    const auto blocks = block_links(system_);
    if (!blocks.empty()) {
      out_ << "\\medskip\n\\begin{tabular}{lrrr}\n\\toprule\nslider block & angle & $\\omega$ & $\\alpha$ \\\\\n"
              " & $\\mathrm{deg}$ & $\\mathrm{rad/s}$ & $\\mathrm{rad/s^2}$ \\\\\n\\midrule\n";
      for (const auto& block : blocks) {
        out_ << latex_escape_text(system_.linkage->links[block.first - 1].name) << " & $" << latex_number(v[0], 5)
             << "$ & $" << latex_number(v[1], 5) << "$ & $" << latex_number(v[2], 5) << "$ \\\\\n";
        v += 3;
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
    const auto pair = [](const double* c) { return "$(" + latex_number(c[0], 5) + ",\\ " + latex_number(c[1], 5) + ")$"; };
    out_ << "\\medskip\n\\begin{tabular}{lccc}\n\\toprule\nslider & relative velocity $\\mathbf{v}^r$ & relative "
            "acceleration $\\mathbf{a}^r$ & Coriolis $2\\boldsymbol{\\omega}\\times\\mathbf{v}^r$ \\\\\n & $\\mathrm{"
         << l << "/s}$ & $\\mathrm{" << l << "/s^2}$ & $\\mathrm{" << l << "/s^2}$ \\\\\n\\midrule\n";
    for (const LinkageFrames::Slider& slider : system_.linkage->frames.sliders) {
      out_ << latex_escape_text(system_.linkage->joints[slider.joint].name) << " & " << pair(v) << " & " << pair(v + 2)
           << " & " << pair(v + 4) << " \\\\\n";
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
        const LinkageFrames::Slider& slider = system_.linkage->frames.sliders[g.slider];
        // B on link 3 is B_3, as the seed writes it (braced: the point's name may carry a subscript).
        const std::string& link = system_.linkage->links[slider.guide - 1].name;
        out_ << "${" << latex_symbol_name(system_.points[g.point].name) << "}_{\\mathrm{" << latex_escape_text(link)
             << "}}$ & " << latex_escape_text(link)
             << " & " << pair(v) << " & " << pair(v + 2) << " \\\\\n";
        v += 4;
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
    const auto turnings = relative_turnings(system_);
    if (!turnings.empty()) {
      out_ << "\\medskip\n\\begin{tabular}{llrr}\n\\toprule\nlinks & at & relative $\\omega$ & relative $\\alpha$ "
              "\\\\\n & & $\\mathrm{rad/s}$ & $\\mathrm{rad/s^2}$ \\\\\n\\midrule\n";
      for (const RelativeTurning& r : turnings) {
        out_ << latex_escape_text(system_.linkage->links[r.block - 1].name) << ", "
             << latex_escape_text(system_.linkage->links[r.other - 1].name) << " & "
             << latex_escape_text(system_.linkage->joints[r.joint].name) << " & $" << latex_symbol_name(r.rate_name)
             << " = " << latex_number(v[0], 5) << "$ & $" << latex_symbol_name(r.second_rate_name) << " = "
             << latex_number(v[1], 5) << "$ \\\\\n";
        v += 2;
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
  }

  // Spatial chains: each point's position, velocity and acceleration as vectors, and
  // each frame's angular velocity and acceleration (observer basis).
  void spatial_tables(const MotionState& s) {
    const std::string l = latex_escape_text(scale_.length_unit);
    const auto triple = [&](const std::array<double, 3>& v, double f) {
      return "$(" + latex_number(v[0] / f, 5) + ",\\ " + latex_number(v[1] / f, 5) + ",\\ " + latex_number(v[2] / f, 5) + ")$";
    };
    if (!system_.points.empty()) {
      out_ << "\\medskip\n\\begin{tabular}{lccc}\n\\toprule\npoint & position ($\\mathrm{" << l
           << "}$) & velocity ($\\mathrm{" << l << "/s}$) & acceleration ($\\mathrm{" << l
           << "/s^2}$) \\\\\n\\midrule\n";
      for (std::size_t p = 0; p < system_.points.size(); ++p) {
        const PointMotion& m = s.points[p];
        out_ << latex_escape_text(system_.points[p].name) << " & " << triple(m.position, scale_.length) << " & "
             << triple(m.velocity, scale_.length) << " & " << triple(m.acceleration, scale_.length) << " \\\\\n";
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
    out_ << "\\medskip\n\\begin{tabular}{lcc}\n\\toprule\nframe & $\\boldsymbol{\\omega}$ relative to "
         << latex_escape_text(chain_observer(system_)) << " ($\\mathrm{rad/s}$) & $\\boldsymbol{\\alpha}$ "
         << "($\\mathrm{rad/s^2}$) \\\\\n\\midrule\n";
    for (std::size_t f = 0; f < system_.frames.size(); ++f) {
      out_ << latex_escape_text(system_.frames[f].name) << " & " << triple(s.frames[f].angular_velocity, 1) << " & "
           << triple(s.frames[f].angular_acceleration, 1) << " \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n";
  }

  void point_table(const MotionState& s) {
    // Planar points (the drawing and the table's columns are 2-D).
    const std::string l = scale_.length_unit;
    out_ << "\\medskip\n\\begin{tabular}{lrrrrrrrr}\n\\toprule\npoint & $x$ & $y$ & $v_x$ & $v_y$ & $|v|$ & $a_x$ & "
            "$a_y$ & $|a|$ \\\\\n & \\multicolumn{2}{c}{$\\mathrm{"
         << l << "}$} & \\multicolumn{3}{c}{$\\mathrm{" << l << "/s}$} & \\multicolumn{3}{c}{$\\mathrm{" << l
         << "/s^2}$} \\\\\n\\midrule\n";
    for (std::size_t p = 0; p < system_.points.size(); ++p) {
      const PointMotion& m = s.points[p];
      const double f = scale_.length;
      out_ << latex_escape_text(system_.points[p].name);
      // A component that is rounding noise next to its vector's length prints as 0, not 3e-15.
      const auto shown = [](double v, double size) { return std::fabs(v) <= 1e-12 * size ? 0.0 : v; };
      const double r = std::hypot(m.position[0], m.position[1]), speed = m.speed(), a = m.acceleration_magnitude();
      for (double v : {shown(m.position[0], r), shown(m.position[1], r), shown(m.velocity[0], speed),
                       shown(m.velocity[1], speed), speed, shown(m.acceleration[0], a), shown(m.acceleration[1], a), a})
        out_ << " & $" << latex_number(v / f, 5) << "$";
      out_ << " \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n";
  }

  // The solved formulas with the numbers put in, as a worked solution shows them:
  // lengths in the output unit, angles in degrees, rates as computed.
  void substitution(const MotionState& s) {
    // Braced, so that a suffix (the degree sign) never follows another superscript
    // (a number in powers of ten: 10^{-15}).
    auto shown = [](double value, const std::string& suffix) {
      const std::string number = latex_number(value, 5);
      const bool power = !suffix.empty() && number.find('^') != std::string::npos;
      return "(" + (power ? "{" + number + "}" : number) + suffix + ")";
    };
    auto coordinate = [&](Dimension dimension, double si) {
      return dimension == Dimension::angle ? shown(to_degrees(si), "^{\\circ}") : shown(si / scale_.length, "");
    };
    TextbookForm::SymbolTexts numbers;
    for (const SystemParameter& parameter : system_.parameters) {
      numbers[parameter.symbol] = parameter.dimension == Dimension::number ? shown(parameter.value, "")
                                                                           : coordinate(parameter.dimension, parameter.value);
    }
    const Driver& input = system_.input;
    numbers[input.symbol] = coordinate(input.dimension, s.input);
    numbers[input.rate] = shown(scale_.rate(input.dimension, s.input_rate), "");
    numbers[input.second_rate] = shown(scale_.rate(input.dimension, s.input_second_rate), "");
    for (std::size_t j = 0; j < system_.unknowns.size(); ++j) {
      const Coordinate& q = system_.unknowns[j];
      numbers[q.symbol] = coordinate(q.dimension, s.q[j]);
      numbers[q.rate] = shown(scale_.rate(q.dimension, s.qd[j]), "");
      numbers[q.second_rate] = shown(scale_.rate(q.dimension, s.qdd[j]), "");
    }
    out_ << "Numeric substitution (lengths in " << latex_escape_text(scale_.length_unit) << "):\n\\begin{align*}\n";
    std::vector<std::string> rows;
    for (int order = 1; order <= 2; ++order) {
      for (const SolvingBlock& block : d_.blocks) {
        for (std::size_t j : block.unknowns) {
          const Coordinate& q = system_.unknowns[j];
          const double value = scale_.rate(q.dimension, order == 1 ? s.qd[j] : s.qdd[j]);
          const ex& formula = order == 1 ? d_.solved_rates[j] : d_.solved_second_rates[j];
          const auto lines = textbook_.latex_lines(formula, q.symbol, &numbers, kLatexLineBudget);
          const std::string result = " = " + latex_number(value) + "\\,\\mathrm{" +
                                     (order == 1 ? scale_.rate_unit(q.dimension) : scale_.second_rate_unit(q.dimension)) + "}";
          for (const LatexRow& row : latex_broken_rows(to_latex(order == 1 ? q.rate : q.second_rate), lines, result))
            rows.push_back(row.text);
        }
      }
    }
    align_rows(rows);
  }

  void align_rows(const std::vector<LatexRow>& rows) {
    std::vector<std::string> texts;
    for (const LatexRow& row : rows) texts.push_back(row.comment.empty() ? row.text : row.text + " %% " + row.comment);
    align_rows(texts);
  }

  // Rows of an align*; text after " %% " in a row becomes a comment after the row's end.
  void align_rows(const std::vector<std::string>& rows) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const auto comment = rows[r].find(" %% ");
      out_ << "  " << rows[r].substr(0, comment) << (r + 1 < rows.size() && !is_intertext(rows[r]) ? " \\\\" : "");
      if (comment != std::string::npos) out_ << " % " << rows[r].substr(comment + 4);
      out_ << "\n";
    }
    out_ << "\\end{align*}\n";
  }

  // Points sliding along turning links: the acceleration's named terms (derived
  // once, in the symbolic stage).
  void sliding_link_terms() {
    for (const SlidingLinkTerms& t : d_.sliding_links) {
      const std::string e = latex_exp(t.angle);
      out_ << "In loop " << latex_escape_text(system_.groups[t.group].name) << ", the point at the end of $"
           << to_latex(t.length) << "\\," << e
           << "$ slides along a turning link: its acceleration has the relative term $" << to_latex(t.relative)
           << "\\," << e << "$ along the link, the Coriolis term $2\\," << to_latex(t.coriolis) << "\\,i\\," << e
           << "$, and the terms of the link's own rotation, $(" << to_latex(t.tangential) << ")\\,i\\," << e
           << "$ and $-" << to_latex(t.normal) << "\\," << e << "$.\n\n";
    }
  }
};

class WorkedSolutionPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::document; }
  const char* name() const override { return "latex"; }

  void print(std::ostream& out, const PrintJob& job) const override {
    DocumentWriter writer(out, job.model);
    if (!job.fragment) writer.preamble();
    writer.data();
    if (is_driven_chain(job.model.system)) {  // worked out at the instant, as seed 000
      writer.chain(job.basis);
    } else if (job.method == DerivationMethod::loops) {
      writer.loops();
      writer.velocity();
      writer.acceleration();
    } else {
      writer.loops();
      writer.by_method(job.method);
    }
    if (job.values)
      for (const MotionState& s : *job.values) writer.results(s);
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
