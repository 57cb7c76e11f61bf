#include <kinema/engine/printers/latex/pgfplots.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <kinema/engine/printers/latex/latex_format.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/output_scale.hpp>

namespace kinema {
namespace {

class PlotWriter {
 public:
  PlotWriter(std::ostream& out, const ConstraintSystem& system, const MotionTable& sweep)
      : out_(out), system_(system), sweep_(sweep), scale_(system) {
    // A crank's turn from its file value, drawn from 0 to 360 deg: the rows past 360 deg
    // first (wrapped), then the rest, with a break where the two parts meet.
    const bool turn = system.input.dimension == Dimension::angle && sweep.size() > 1 &&
                      scale_.input(sweep.input(sweep.size() - 1)) - scale_.input(sweep.input(0)) >= 359.999;
    std::size_t wrap = sweep.size();
    if (turn) {
      for (std::size_t row = 0; row < sweep.size(); ++row)
        if (wrapped(sweep.input(row)) < wrapped(sweep.input(0)) - 1e-9) {
          wrap = row;
          break;
        }
    }
    for (std::size_t row = wrap; row < sweep.size(); ++row) rows_.push_back(row);
    if (wrap < sweep.size()) rows_.push_back(kBreak);
    for (std::size_t row = 0; row < wrap; ++row) rows_.push_back(row);
    turn_ = turn;
  }

  void write() {
    if (sweep_.empty()) return;
    const Dimension kind = system_.input.dimension;
    const std::string input = to_latex(system_.input.symbol);
    out_ << "\\clearpage\n\\subsection*{Over the input range}\nThe unknowns, their rates and second rates";
    if (!system_.points.empty()) out_ << ", and the speeds of the points";
    out_ << " against $" << input << "$. Gaps: positions that cannot be assembled; red dashed "
            "lines: singular positions (toggle or dead centre), where the rates are not defined.\n\n";
    const std::string x_label = "$" + input + "$ [$\\mathrm{" + scale_.coordinate_unit(kind) + "}$]";
    int plotted = 0;
    for (int order = 0; order < 3; ++order) {
      for (Dimension dim : {Dimension::angle, Dimension::length}) {
        std::vector<std::size_t> members;
        for (std::size_t j = 0; j < system_.unknowns.size(); ++j)
          if (system_.unknowns[j].dimension == dim) members.push_back(j);
        if (members.empty()) continue;
        const std::string what = order == 0 ? (dim == Dimension::angle ? "angles" : "lengths")
                                            : order == 1 ? "rates" : "second rates";
        const std::string y_unit = order == 0 ? scale_.coordinate_unit(dim)
                                              : order == 1 ? scale_.rate_unit(dim) : scale_.second_rate_unit(dim);
        begin_axis(x_label, what + " [$\\mathrm{" + y_unit + "}$]", plotted++);
        for (std::size_t j : members) {
          out_ << "\\addplot+[mark=none, thick] coordinates {";
          for (std::size_t row : rows_) {
            if (row == kBreak) {
              out_ << " (nan,nan)";
              continue;
            }
            const MotionState s = sweep_[row];
            double y = NAN;
            if (order == 0 && s.status != Status::unassembled) {
              y = scale_.unwrapped(dim, s.q[j]);  // continuous curves without +-180 deg jumps
            } else if (order > 0 && s.status == Status::ok) {
              y = scale_.rate(dim, order == 1 ? s.qd[j] : s.qdd[j]);
            }
            point(x_of(s.input), y);
          }
          const Coordinate& q = system_.unknowns[j];
          out_ << " };\n\\addlegendentry{$" << to_latex(order == 0 ? q.symbol : order == 1 ? q.rate : q.second_rate)
               << "$}\n";
        }
        singular_marks();
        end_axis();
      }
    }
    if (!system_.points.empty()) {
      begin_axis(x_label, "speed [$\\mathrm{" + scale_.length_unit + "/s}$]", plotted++);
      for (std::size_t p = 0; p < system_.points.size(); ++p) {
        out_ << "\\addplot+[mark=none, thick] coordinates {";
        for (std::size_t row : rows_) {
          if (row == kBreak) {
            out_ << " (nan,nan)";
            continue;
          }
          point(x_of(sweep_.input(row)), sweep_.status(row) == Status::ok ? sweep_.point(row, p).speed() / scale_.length : NAN);
        }
        out_ << " };\n\\addlegendentry{" << latex_escape_text(system_.points[p].name) << "}\n";
      }
      singular_marks();
      end_axis();
    }
    out_ << "\n";
    if (system_.frames.empty()) paths();
  }

 private:
  // Each planar point's path over the run (a coupler curve when it is on the coupler),
  // to one scale in x and y.
  void paths() {
    std::vector<std::size_t> moving;
    for (std::size_t p = 0; p < system_.points.size(); ++p) {
      double reach = 0;
      for (std::size_t row = 0; row < sweep_.size(); ++row)
        if (sweep_.status(row) == Status::ok) reach = std::max(reach, sweep_.point(row, p).speed());
      if (reach > 0) moving.push_back(p);
    }
    if (moving.empty()) return;
    const std::string l = "[$\\mathrm{" + scale_.length_unit + "}$]";
    out_ << "\\medskip\n\\noindent Paths of the points over the run (coupler curves of points on a coupler), "
            "to one scale in $x$ and $y$:\n\n\\begin{center}\n\\begin{tikzpicture}\n\\begin{axis}[width=0.7\\linewidth, "
            "axis equal image, xlabel={$x$ "
         << l << "}, ylabel={$y$ " << l
         << "}, unbounded coords=jump, legend style={font=\\footnotesize, at={(0.5,1.02)}, anchor=south, "
            "legend columns=-1}]\n";
    for (std::size_t p : moving) {
      out_ << "\\addplot+[mark=none, thick] coordinates {";
      for (std::size_t row = 0; row < sweep_.size(); ++row) {
        if (sweep_.status(row) == Status::unassembled) {
          out_ << " (nan,nan)";
          continue;
        }
        const PointMotion m = sweep_.point(row, p);
        out_ << " (" << format_fixed(m.position[0] / scale_.length) << "," << format_fixed(m.position[1] / scale_.length) << ")";
      }
      out_ << " };\n\\addlegendentry{" << latex_escape_text(system_.points[p].name) << "}\n";
    }
    out_ << "\\end{axis}\n\\end{tikzpicture}\n\\end{center}\n\n";
  }

  static constexpr std::size_t kBreak = static_cast<std::size_t>(-1);
  std::ostream& out_;
  const ConstraintSystem& system_;
  const MotionTable& sweep_;
  OutputScale scale_;
  std::vector<std::size_t> rows_;  // in the order drawn; kBreak: a gap
  bool turn_ = false;

  // The input as plotted: in [0, 360) deg for a crank's turn.
  double wrapped(double si) const {
    const double x = scale_.input(si);
    if (system_.input.dimension != Dimension::angle) return x;
    const double w = std::fmod(x, 360.0);
    return w < 0 ? w + 360.0 : w;
  }
  double x_of(double si) const { return turn_ ? wrapped(si) : scale_.input(si); }

  void point(double x, double y) {
    out_ << " (" << format_fixed(x) << "," << (std::isfinite(y) ? format_fixed(y) : "nan") << ")";
  }

  void begin_axis(const std::string& x_label, const std::string& y_label, int index) {
    out_ << (index % 2 ? "\\hfill" : "\\noindent") << "\\begin{minipage}{0.48\\linewidth}\n"
         << "\\begin{tikzpicture}\n\\begin{axis}[width=0.85\\linewidth, height=5.5cm, xlabel={" << x_label
         << "}, ylabel={" << y_label
         << "}, " << (turn_ ? "xmin=0, xmax=360, xtick={0,90,180,270,360}, " : "")
         << "unbounded coords=jump, legend style={font=\\footnotesize, at={(0.5,1.02)}, anchor=south, "
         << "legend columns=-1}]\n";
  }
  void end_axis() { out_ << "\\end{axis}\n\\end{tikzpicture}\n\\end{minipage}\n"; }

  void singular_marks() {
    for (std::size_t row = 0; row < sweep_.size(); ++row) {
      if (sweep_.status(row) != Status::singular) continue;
      const std::string x = format_fixed(x_of(sweep_.input(row)));
      out_ << "\\draw[red, dashed] ({axis cs:" << x << ",0}|-{rel axis cs:0,0}) -- ({axis cs:" << x
           << ",0}|-{rel axis cs:0,1});\n";
    }
  }
};

}  // namespace

void write_pgfplots(std::ostream& out, const ConstraintSystem& system, const MotionTable& sweep) {
  PlotWriter(out, system, sweep).write();
}

}  // namespace kinema
