// `kinema latex`: a worked solution in LaTeX — data, vector loops, velocity and
// acceleration analysis, results at the requested input values, a TikZ drawing
// of the mechanism with velocity vectors, and pgfplots over a revolution.
#include <cmath>
#include <complex>
#include <cstdio>
#include <sstream>

#include <kinema/engine/symbolic/expression_parts.hpp>
#include <kinema/engine/printers/latex/latex_names.hpp>
#include <kinema/engine/printers/printers.hpp>
#include <kinema/engine/symbolic/trig_simplify.hpp>

namespace kinema {
namespace {

using GiNaC::ex;

std::string number(double value, int digits = 6) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value == 0 ? 0.0 : value);
  std::string text = buffer;
  const auto e = text.find('e');
  if (e != std::string::npos) {  // 1e-05 -> 1\cdot10^{-5} for text mode
    const int exponent = std::stoi(text.substr(e + 1));
    text = text.substr(0, e) + "\\cdot 10^{" + std::to_string(exponent) + "}";
  }
  return text;
}

// Plain decimal for TikZ/pgfplots coordinates.
std::string coordinate(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", value);
  return buffer;
}


}  // namespace

namespace {

// Values of every symbol at one state, for numeric evaluation of loop terms.
GiNaC::exmap state_values(const Derivation& d, const MotionState& s) {
  GiNaC::exmap values;
  for (std::size_t p = 0; p < d.closure.parameters.size(); ++p)
    values[d.closure.parameters[p]] = d.closure.parameter_values[p];
  values[d.closure.input] = s.input;
  for (std::size_t j = 0; j < d.closure.unknowns.size(); ++j) values[d.closure.unknowns[j]] = s.q[j];
  return values;
}

std::complex<double> evaluate_complex(const ex& e, const GiNaC::exmap& values) {
  const ex v = GiNaC::evalf(e.subs(values));
  if (!GiNaC::is_a<GiNaC::numeric>(v)) return {0, 0};
  const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(v);
  return {GiNaC::real(n).to_double(), GiNaC::imag(n).to_double()};
}

class DocumentWriter {
 public:
  DocumentWriter(std::ostream& out, const Mechanism& m, const Derivation& d)
      : out_(out), m_(m), d_(d), names_(latex_symbols(m, d)), scale_(m) {}

  void preamble() {
    out_ << "\\documentclass[11pt]{article}\n"
         << "\\usepackage[margin=2cm]{geometry}\n"
         << "\\usepackage{amsmath,booktabs}\n"
         << "\\usepackage{tikz}\n\\usetikzlibrary{patterns}\n"
         << "\\usepackage{pgfplots}\n\\pgfplotsset{compat=1.16}\n"
         << "\\allowdisplaybreaks\n"
         << "\\begin{document}\n";
  }

  void data() {
    out_ << "\\section*{" << latex_escape_text(m_.title) << "}\n";
    if (!m_.description.empty()) out_ << latex_escape_text(m_.description) << "\n\n";
    out_ << "\\subsection*{Data}\n\\begin{tabular}{ll}\n\\toprule\nparameter & value \\\\\n\\midrule\n";
    for (std::size_t p = 0; p < m_.parameters.size(); ++p) {
      const Parameter& parameter = m_.parameters[p];
      out_ << "$" << latex_symbol_name(parameter.name) << "$ & ";
      if (parameter.quantity) {
        out_ << latex_escape_text(parameter.text);
      } else {
        const ex formula = d_.closure.parameter_formulas.at(d_.closure.parameters[p]);
        out_ << "$" << to_latex(formula, names_) << " = " << number(d_.closure.parameter_values[p]) << "$";
      }
      out_ << " \\\\\n";
    }
    const Dimension kind = m_.input.dimension;
    out_ << "\\bottomrule\n\\end{tabular}\n\n"
         << "Input: $" << symbol(d_.closure.input) << "$ (" << (kind == Dimension::angle ? "crank angle" : "slider position")
         << "), $" << symbol(d_.input_rate) << " = " << number(scale_.rate(kind, m_.input.rate)) << "\\,\\mathrm{"
         << unit(scale_.rate_unit(kind)) << "}$ (negative: " << (kind == Dimension::angle ? "clockwise" : "decreasing")
         << "), $" << symbol(d_.input_second_rate) << " = " << number(scale_.rate(kind, m_.input.second_rate))
         << "\\,\\mathrm{" << unit(scale_.second_rate_unit(kind)) << "}$. Unknowns: ";
    for (std::size_t j = 0; j < m_.unknowns.size(); ++j)
      out_ << (j ? ", " : "") << "$" << symbol(d_.closure.unknowns[j]) << "$";
    out_ << ". Angles are measured counter-clockwise from the $x$ axis.\n\n";
  }

  void loops() {
    out_ << "\\subsection*{Vector loops}\nEach loop closes ($=0$); its real and imaginary parts are the scalar "
            "equations $\\Phi(q," << symbol(d_.closure.input) << ")=0$:\n\\begin{align*}\n";
    std::vector<std::string> rows;
    for (std::size_t k = 0; k < m_.loops.size(); ++k) {
      rows.push_back("\\text{" + latex_escape_text(m_.loops[k].name) + ":}\\quad & " +
                     latex_vector_loop(d_.closure.loop_vectors[k], names_, m_.loops[k].complex_formula) + " = 0");
      rows.push_back("& " + to_latex(d_.closure.equations[2 * k], names_) + " = 0");
      rows.push_back("& " + to_latex(d_.closure.equations[2 * k + 1], names_) + " = 0");
    }
    align_rows(rows);
  }

  void velocity() {
    out_ << "\\subsection*{Velocity analysis}\nDifferentiating the loop equations in time gives the velocity "
            "equations $\\Phi_q\\,\\dot q = -\\Phi_{" << symbol(d_.closure.input) << "}\\,"
         << symbol(d_.input_rate) << "$:\n\\begin{align*}\n";
    std::vector<ex> rates(d_.rates.begin(), d_.rates.end()), rhs;
    for (std::size_t i = 0; i < rates.size(); ++i) rhs.push_back(-d_.input_jacobian(i, 0) * d_.input_rate);
    std::vector<std::string> rows = {"& " + jacobian() + column(rates) + " = " + column(rhs)};
    for (const RateBlock& block : d_.blocks)
      for (std::size_t j : block.unknowns)
        rows.push_back(symbol(d_.rates[j]) + " &= " + to_latex(d_.solved_rates[j], names_) +
                       parse_back(d_.rates[j], d_.solved_rates[j]));
    align_rows(rows);
  }

  void acceleration() {
    out_ << "\\subsection*{Acceleration analysis}\nDifferentiating once more: $\\Phi_q\\,\\ddot q = \\gamma$ with "
            "the same matrix $\\Phi_q$:\n\\begin{align*}\n";
    std::vector<ex> second(d_.second_rates.begin(), d_.second_rates.end());
    std::string gamma = "\\begin{bmatrix}";
    for (std::size_t i = 0; i < second.size(); ++i) gamma += (i ? " \\\\ " : " ") + std::string("\\gamma_{") + std::to_string(i + 1) + "}";
    gamma += " \\end{bmatrix}";
    std::vector<std::string> rows = {"& " + jacobian() + column(second) + " = " + gamma};
    // The right-hand side one row at a time: a column of it would not fit the page.
    for (std::size_t i = 0; i < d_.acceleration_rhs.size(); ++i)
      rows.push_back("\\gamma_{" + std::to_string(i + 1) + "} &= " + to_latex(combine_trig_products(d_.acceleration_rhs[i]), names_));
    for (const RateBlock& block : d_.blocks)
      for (std::size_t j : block.unknowns)
        rows.push_back(symbol(d_.second_rates[j]) + " &= " + to_latex(d_.solved_second_rates[j], names_) +
                       parse_back(d_.second_rates[j], d_.solved_second_rates[j]));
    align_rows(rows);
    coriolis_terms();
  }

  void results(const MotionState& s) {
    const Dimension kind = m_.input.dimension;
    const double shown = kind == Dimension::angle ? s.input * 180.0 / M_PI : s.input / scale_.length;
    out_ << "\\clearpage\n\\subsection*{Results at $" << symbol(d_.closure.input) << " = " << number(shown)
         << "\\,\\mathrm{" << unit(scale_.coordinate_unit(kind)) << "}$}\n";
    if (s.status != Status::ok) {
      out_ << latex_escape_text(s.message) << "\n\n";
      if (s.status == Status::unassembled) return;
    }
    out_ << "\\begin{tabular}{lrrr}\n\\toprule\ncoordinate & value & rate & second rate \\\\\n\\midrule\n";
    for (std::size_t j = 0; j < m_.unknowns.size(); ++j) {
      const Dimension k = m_.unknowns[j].dimension;
      out_ << "$" << symbol(d_.closure.unknowns[j]) << "$ & $" << number(scale_.coordinate(k, s.q[j])) << "\\,\\mathrm{"
           << unit(scale_.coordinate_unit(k)) << "}$ & ";
      if (s.status == Status::ok) {
        out_ << "$" << symbol(d_.rates[j]) << " = " << number(scale_.rate(k, s.qd[j])) << "\\,\\mathrm{"
             << unit(scale_.rate_unit(k)) << "}$ & $" << symbol(d_.second_rates[j]) << " = "
             << number(scale_.rate(k, s.qdd[j])) << "\\,\\mathrm{" << unit(scale_.second_rate_unit(k)) << "}$";
      } else {
        out_ << "undefined & undefined";
      }
      out_ << " \\\\\n";
    }
    out_ << "\\bottomrule\n\\end{tabular}\n\n";
    if (s.status == Status::ok && !m_.points.empty()) {
      const std::string l = unit(scale_.length_unit);
      out_ << "\\medskip\n\\begin{tabular}{lrrrrrrrr}\n\\toprule\npoint & $x$ & $y$ & $v_x$ & $v_y$ & $|v|$ & $a_x$ & "
              "$a_y$ & $|a|$ \\\\\n & \\multicolumn{2}{c}{$\\mathrm{" << l << "}$} & \\multicolumn{3}{c}{$\\mathrm{" << l
           << "/s}$} & \\multicolumn{3}{c}{$\\mathrm{" << l << "/s^2}$} \\\\\n\\midrule\n";
      for (std::size_t p = 0; p < m_.points.size(); ++p) {
        const PointMotion& pm = s.points[p];
        const double f = scale_.length;
        out_ << latex_escape_text(m_.points[p].name);
        for (double v : {pm.x, pm.y, pm.vx, pm.vy, std::hypot(pm.vx, pm.vy), pm.ax, pm.ay, std::hypot(pm.ax, pm.ay)})
          out_ << " & $" << number(v / f, 5) << "$";
        out_ << " \\\\\n";
      }
      out_ << "\\bottomrule\n\\end{tabular}\n\n";
    }
    if (s.status == Status::ok) substitution(s);
    drawing(s);
  }

  // The solved formulas with the numbers put in, as a worked solution shows them:
  // lengths in the output unit, angles in degrees, rates as computed.
  void substitution(const MotionState& s) {
    const auto& c = d_.closure;
    auto shown = [](double value, const std::string& suffix) {
      return "(" + number(value, 5) + suffix + ")";
    };
    auto length_like = [&](const ex& e) {
      for (std::size_t p = 0; p < m_.parameters.size(); ++p) {
        const auto& q = m_.parameters[p].quantity;
        if (q && q->dimension == Dimension::length && e.has(c.parameters[p])) return true;
      }
      return false;
    };
    GiNaC::exmap numbers;
    auto put = [&](const GiNaC::realsymbol& symbol, const std::string& tex) {
      numbers[symbol] = GiNaC::realsymbol(symbol.get_name(), tex);
    };
    for (std::size_t p = 0; p < m_.parameters.size(); ++p) {
      const auto& q = m_.parameters[p].quantity;
      const double v = c.parameter_values[p];
      const bool angle = q && q->dimension == Dimension::angle;
      const bool length = q ? q->dimension == Dimension::length
                            : length_like(c.parameter_formulas.at(c.parameters[p]));
      put(c.parameters[p], angle ? shown(v * 180.0 / M_PI, "^{\\circ}") : shown(length ? v / scale_.length : v, ""));
    }
    const Dimension kind = m_.input.dimension;
    put(c.input, kind == Dimension::angle ? shown(s.input * 180.0 / M_PI, "^{\\circ}") : shown(s.input / scale_.length, ""));
    put(d_.input_rate, shown(scale_.rate(kind, s.input_rate), ""));
    put(d_.input_second_rate, shown(scale_.rate(kind, s.input_second_rate), ""));
    for (std::size_t j = 0; j < m_.unknowns.size(); ++j) {
      const Dimension k = m_.unknowns[j].dimension;
      put(c.unknowns[j], k == Dimension::angle ? shown(s.q[j] * 180.0 / M_PI, "^{\\circ}") : shown(s.q[j] / scale_.length, ""));
      put(d_.rates[j], shown(scale_.rate(k, s.qd[j]), ""));
      put(d_.second_rates[j], shown(scale_.rate(k, s.qdd[j]), ""));
    }
    out_ << "Numeric substitution (lengths in " << latex_escape_text(scale_.length_unit) << "):\n\\begin{align*}\n";
    std::vector<std::string> rows;
    for (const auto* solved : {&d_.solved_rates, &d_.solved_second_rates}) {
      const bool first = solved == &d_.solved_rates;
      for (const RateBlock& block : d_.blocks) {
        for (std::size_t j : block.unknowns) {
          const Dimension k = m_.unknowns[j].dimension;
          const double value = scale_.rate(k, first ? s.qd[j] : s.qdd[j]);
          std::ostringstream substituted;
          substituted << GiNaC::latex << (*solved)[j].subs(numbers);
          rows.push_back(symbol(first ? d_.rates[j] : d_.second_rates[j]) + " &= " + substituted.str() + " = " +
                         number(value) + "\\,\\mathrm{" + unit(first ? scale_.rate_unit(k) : scale_.second_rate_unit(k)) + "}");
        }
      }
    }
    align_rows(rows);
  }

  void plots(const MotionTable& sweep) {
    if (sweep.empty()) return;
    const Dimension kind = m_.input.dimension;
    out_ << "\\clearpage\n\\subsection*{Over the input range}\nThe unknowns, their rates and second rates";
    if (!m_.points.empty()) out_ << ", and the speeds of the points";
    out_ << " against $" << symbol(d_.closure.input) << "$. Gaps: positions that cannot be assembled; red dashed "
            "lines: singular positions (toggle or dead centre), where the rates are not defined.\n\n";
    const std::string x_label = "$" + symbol(d_.closure.input) + "$ [$\\mathrm{" + unit(scale_.coordinate_unit(kind)) + "}$]";
    auto x_of = [&](const MotionState& s) {
      return kind == Dimension::angle ? s.input * 180.0 / M_PI : s.input / scale_.length;
    };
    int plotted = 0;
    for (int order = 0; order < 3; ++order) {
      for (Dimension dim : {Dimension::angle, Dimension::length}) {
        std::vector<std::size_t> members;
        for (std::size_t j = 0; j < m_.unknowns.size(); ++j)
          if (m_.unknowns[j].dimension == dim) members.push_back(j);
        if (members.empty()) continue;
        const std::string what = order == 0 ? (dim == Dimension::angle ? "angles" : "lengths")
                                            : order == 1 ? "rates" : "second rates";
        const std::string y_unit = order == 0 ? scale_.coordinate_unit(dim)
                                              : order == 1 ? scale_.rate_unit(dim) : scale_.second_rate_unit(dim);
        begin_axis(x_label, what + " [$\\mathrm{" + unit(y_unit) + "}$]", plotted++);
        for (std::size_t j : members) {
          out_ << "\\addplot+[mark=none, thick] coordinates {";
          for (const MotionState& s : sweep) {
            double y = NAN;
            if (order == 0 && s.status != Status::unassembled) {
              // Unwrapped angles: continuous curves without +-180 deg jumps.
              y = dim == Dimension::angle ? s.q[j] * 180.0 / M_PI : s.q[j] / scale_.length;
            } else if (order > 0 && s.status == Status::ok) {
              y = scale_.rate(dim, order == 1 ? s.qd[j] : s.qdd[j]);
            }
            out_ << " (" << coordinate(x_of(s)) << "," << (std::isfinite(y) ? coordinate(y) : "nan") << ")";
          }
          const ex& sym = order == 0 ? ex(d_.closure.unknowns[j]) : order == 1 ? ex(d_.rates[j]) : ex(d_.second_rates[j]);
          out_ << " };\n\\addlegendentry{$" << to_latex(sym, names_) << "$}\n";
        }
        singular_marks(sweep, x_of);
        end_axis();
      }
    }
    if (!m_.points.empty()) {
      begin_axis(x_label, "speed [$\\mathrm{" + unit(scale_.length_unit) + "/s}$]", plotted++);
      for (std::size_t p = 0; p < m_.points.size(); ++p) {
        out_ << "\\addplot+[mark=none, thick] coordinates {";
        for (const MotionState& s : sweep) {
          const double y = s.status == Status::ok ? std::hypot(s.points[p].vx, s.points[p].vy) / scale_.length : NAN;
          out_ << " (" << coordinate(x_of(s)) << "," << (std::isfinite(y) ? coordinate(y) : "nan") << ")";
        }
        out_ << " };\n\\addlegendentry{" << latex_escape_text(m_.points[p].name) << "}\n";
      }
      singular_marks(sweep, x_of);
      end_axis();
    }
    out_ << "\n";
  }

  void end() { out_ << "\\end{document}\n"; }

 private:
  std::ostream& out_;
  const Mechanism& m_;
  const Derivation& d_;
  GiNaC::exmap names_;
  OutputScale scale_;

  std::string symbol(const ex& s) const { return to_latex(s, names_); }
  static std::string unit(const std::string& u) {
    std::string out;
    for (char c : u) out += c == '^' ? std::string("^") : std::string(1, c);
    return out;
  }

  // Rows of an align*; text after " %% " in a row becomes a comment after the row's end.
  void align_rows(const std::vector<std::string>& rows) {
    for (std::size_t r = 0; r < rows.size(); ++r) {
      const auto comment = rows[r].find(" %% ");
      out_ << "  " << rows[r].substr(0, comment) << (r + 1 < rows.size() ? " \\\\" : "");
      if (comment != std::string::npos) out_ << " % " << rows[r].substr(comment + 4);
      out_ << "\n";
    }
    out_ << "\\end{align*}\n";
  }

  // "% kinema: name = formula" in GiNaC syntax, so the formula can be read back exactly.
  static std::string parse_back(const GiNaC::realsymbol& symbol, const ex& formula) {
    std::ostringstream text;
    text << " %% kinema: " << symbol.get_name() << " = " << formula;
    return text.str();
  }

  std::string column(const std::vector<ex>& entries) const { return latex_column(entries, names_); }
  std::string jacobian() const { return latex_matrix(d_.jacobian, names_); }

  // A term r*exp(I*phi) with r and phi both moving: a point sliding along a
  // turning link. Its acceleration splits into the textbook's named terms.
  void coriolis_terms() {
    std::vector<std::string> sentences;
    for (std::size_t k = 0; k < m_.loops.size(); ++k) {
      const ex loop = d_.closure.loop_vectors[k].expand();
      std::vector<ex> terms;
      if (GiNaC::is_a<GiNaC::add>(loop)) for (const ex& t : loop) terms.push_back(t);
      else terms.push_back(loop);
      for (const ex& term : terms) {
        const LinkVector link = split_link_vector(term);
        if (!link.polar) continue;
        const ex& length = link.length;
        const ex dl = d_.time_derivative(length), angle_rate = d_.time_derivative(link.angle);
        if (dl.is_zero() || angle_rate.is_zero()) continue;
        const ex ddl = d_.time_derivative(dl);
        const std::string e = latex_exp(link.angle, names_);
        sentences.push_back("In loop " + latex_escape_text(m_.loops[k].name) + ", the point at the end of $" +
                            to_latex(length, names_) + "\\," + e +
                            "$ slides along a turning link: its acceleration has the relative term $" +
                            to_latex(ddl, names_) + "\\," + e + "$ along the link, the Coriolis term $2\\," +
                            to_latex(dl * angle_rate, names_) + "\\,i\\," + e +
                            "$, and the terms of the link's own rotation, $(" + to_latex(length * d_.time_derivative(angle_rate), names_) +
                            ")\\,i\\," + e + "$ and $-" + to_latex(length * angle_rate * angle_rate, names_) + "\\," + e + "$.");
      }
    }
    for (const auto& s : sentences) out_ << s << "\n\n";
  }

  void begin_axis(const std::string& x_label, const std::string& y_label, int index) {
    out_ << (index % 2 ? "\\hfill" : "\\noindent") << "\\begin{minipage}{0.48\\linewidth}\n"
         << "\\begin{tikzpicture}\n\\begin{axis}[width=\\linewidth, height=5.5cm, xlabel={" << x_label
         << "}, ylabel={" << y_label << "}, unbounded coords=jump, legend style={font=\\footnotesize, at={(0.5,1.02)}, anchor=south, "
         << "legend columns=-1}]\n";
  }
  void end_axis() { out_ << "\\end{axis}\n\\end{tikzpicture}\n\\end{minipage}\n"; }

  template <class X>
  void singular_marks(const MotionTable& sweep, X x_of) {
    for (const MotionState& s : sweep) {
      if (s.status != Status::singular) continue;
      out_ << "\\draw[red, dashed] ({axis cs:" << coordinate(x_of(s)) << ",0}|-{rel axis cs:0,0}) -- ({axis cs:"
           << coordinate(x_of(s)) << ",0}|-{rel axis cs:0,1});\n";
    }
  }

  void drawing(const MotionState& s) {
    const GiNaC::exmap values = state_values(d_, s);
    struct Segment {
      std::complex<double> from, to;
      enum Kind { ground, link, slider } kind;
    };
    std::vector<Segment> segments;
    std::vector<std::complex<double>> extent = {{0, 0}};
    for (const Loop& loop : m_.loops) {
      std::vector<ex> terms;
      if (!loop.complex_formula.empty()) {
        GiNaC::symtab table;
        for (const auto& [symbol, value] : values) table[GiNaC::ex_to<GiNaC::symbol>(symbol).get_name()] = symbol;
        GiNaC::parser reader(table, true);
        try {
          for (const std::string& t : written_terms(loop.complex_formula)) terms.push_back(reader(t));
        } catch (const std::exception&) {
          terms = {d_.closure.loop_vectors[&loop - &m_.loops[0]]};
        }
      } else {
        terms = {d_.closure.loop_vectors[&loop - &m_.loops[0]]};
      }
      std::complex<double> at = 0;
      for (const ex& term : terms) {
        const std::complex<double> v = evaluate_complex(term, values);
        bool moving = term.has(d_.closure.input);
        bool sliding = m_.input.dimension == Dimension::length && term.has(d_.closure.input);
        for (std::size_t j = 0; j < d_.closure.unknowns.size(); ++j) {
          if (!term.has(d_.closure.unknowns[j])) continue;
          moving = true;
          sliding = sliding || m_.unknowns[j].dimension == Dimension::length;
        }
        segments.push_back({at, at + v, !moving ? Segment::ground : sliding ? Segment::slider : Segment::link});
        at += v;
        extent.push_back(at);
      }
    }
    std::vector<std::complex<double>> points, velocities;
    double fastest = 0;
    if (s.status == Status::ok) {
      for (const PointMotion& p : s.points) {
        points.push_back({p.x, p.y});
        velocities.push_back({p.vx, p.vy});
        fastest = std::max(fastest, std::hypot(p.vx, p.vy));
        extent.push_back({p.x, p.y});
      }
    }
    double min_x = 0, max_x = 0, min_y = 0, max_y = 0;
    for (const auto& p : extent) {
      min_x = std::min(min_x, p.real());
      max_x = std::max(max_x, p.real());
      min_y = std::min(min_y, p.imag());
      max_y = std::max(max_y, p.imag());
    }
    const double size = std::max({max_x - min_x, max_y - min_y, 1e-9});
    const double cm = 9.0 / size;  // drawing units per metre
    const double arrow_cm = 2.5;   // the fastest point's arrow
    const double velocity_scale = fastest > 0 ? arrow_cm / fastest : 0;  // cm per (m/s)
    auto xy = [&](std::complex<double> p) {
      return "(" + coordinate(p.real() * cm) + "," + coordinate(p.imag() * cm) + ")";
    };
    out_ << "\\begin{center}\n\\begin{tikzpicture}[line cap=round]\n";
    for (const Segment& g : segments) {
      if (g.kind == Segment::ground) {
        out_ << "\\draw[gray, dashed] " << xy(g.from) << " -- " << xy(g.to) << ";\n";
        for (const auto& end : {g.from, g.to}) {
          out_ << "\\fill[pattern=north east lines] " << xy(end) << " ++(-0.3,-0.35) rectangle ++(0.6,0.15);\n"
               << "\\draw " << xy(end) << " ++(-0.3,-0.2) -- ++(0.6,0);\n"
               << "\\draw " << xy(end) << " -- ++(-0.15,-0.2) -- ++(0.3,0) -- cycle;\n";
        }
      } else if (g.kind == Segment::slider) {
        // The block sits at the moving end: not on the ground (origin or a ground vector's end).
        bool to_is_ground = std::abs(g.to) < 1e-9 * size;
        for (const Segment& h : segments)
          if (h.kind == Segment::ground && (std::abs(h.to - g.to) < 1e-9 * size || std::abs(h.from - g.to) < 1e-9 * size))
            to_is_ground = true;
        const std::complex<double> block = to_is_ground ? g.from : g.to;
        const std::complex<double> d = g.to - g.from;
        const double angle = std::arg(d) * 180.0 / M_PI;
        out_ << "\\draw[gray, thin] " << xy(g.from - d * 0.1) << " -- " << xy(g.to + d * 0.1) << ";\n"
             << "\\draw[thick, fill=white, rotate around={" << coordinate(angle) << ":" << xy(block) << "}] "
             << xy(block) << " ++(-0.35,-0.2) rectangle ++(0.7,0.4);\n";
      } else {
        out_ << "\\draw[very thick, blue!70!black] " << xy(g.from) << " -- " << xy(g.to) << ";\n";
      }
    }
    for (const Segment& g : segments) {
      for (const auto& end : {g.from, g.to})
        out_ << "\\filldraw[fill=white] " << xy(end) << " circle (0.07);\n";
    }
    for (std::size_t p = 0; p < points.size(); ++p) {
      out_ << "\\fill " << xy(points[p]) << " circle (0.06) node[above left, font=\\small] {"
           << latex_escape_text(m_.points[p].name) << "};\n";
      if (velocity_scale > 0 && std::abs(velocities[p]) > 0) {
        const std::complex<double> tip = velocities[p] * velocity_scale;
        out_ << "\\draw[-latex, red, thick] " << xy(points[p]) << " -- ++(" << coordinate(tip.real()) << ","
             << coordinate(tip.imag()) << ");\n";
      }
    }
    out_ << "\\end{tikzpicture}\n\\end{center}\n";
    const double length_per_cm = 1.0 / cm / scale_.length;
    out_ << "Drawing scale: 1\\,cm = $" << number(length_per_cm, 3) << "$\\," << latex_escape_text(scale_.length_unit);
    if (velocity_scale > 0) {
      out_ << "; velocity vectors (red): 1\\,cm = $" << number(1.0 / velocity_scale / scale_.length, 3) << "$\\,"
           << latex_escape_text(scale_.length_unit) << "/s";
    }
    out_ << ".\n\n";
  }
};

}  // namespace

void print_latex_document(std::ostream& out, const Mechanism& mechanism, const Derivation& derivation,
                          const MotionTable& at_values, const MotionTable& sweep,
                          bool fragment) {
  DocumentWriter writer(out, mechanism, derivation);
  if (!fragment) writer.preamble();
  writer.data();
  writer.loops();
  writer.velocity();
  writer.acceleration();
  for (const MotionState& s : at_values) writer.results(s);
  writer.plots(sweep);
  if (!fragment) writer.end();
}

}  // namespace kinema
