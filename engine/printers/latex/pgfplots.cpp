#include <kinema/engine/printers/latex/pgfplots.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <kinema/engine/printers/latex/latex_format.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/output_scale.hpp>
#include <kinema/engine/report/plot_range.hpp>

namespace kinema {
namespace {

// A value more than this many times the typical size of its plot's values is drawn as a
// gap: a pole (a point at a*tan(theta2) is 1.6e16 a at 90 deg) would squash every other
// value of the plot flat, and pgfplots stops ("divide by 0.0", "Dimension too large") on
// values some 1e6 times apart in the paths' equal scales.
constexpr double kPlotSpan = 1000;

// The largest magnitude a plot draws: kPlotSpan times the 90th percentile of the
// magnitudes of its finite values that print as more than 0 (rounding noise around 0 is not
// a size; a pole's few huge values do not move a percentile); infinite when there are none.
double plot_limit(const std::vector<double>& values) {
  std::vector<double> sizes;
  for (const double v : values)
    if (std::isfinite(v) && std::fabs(v) >= 5e-7) sizes.push_back(std::fabs(v));  // format_fixed's 6 decimals
  if (sizes.empty()) return INFINITY;
  const auto percentile = sizes.begin() + (sizes.size() * 9) / 10;
  std::nth_element(sizes.begin(), percentile, sizes.end());
  return kPlotSpan * *percentile;
}

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
    out_ << kLatexPartBreak << "\\subsection*{Over the input range}\nThe unknowns, their rates and second rates";
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
        std::vector<std::vector<double>> curves;  // each member's values, one per row of rows_
        for (std::size_t j : members) {
          std::vector<double>& ys = curves.emplace_back();
          for (std::size_t row : rows_) {
            double y = NAN;
            if (row != kBreak) {
              const MotionState s = sweep_[row];
              if (order == 0 && s.status != Status::unassembled) {
                y = scale_.unwrapped(dim, s.q[j]);  // continuous curves without +-180 deg jumps
              } else if (order > 0 && s.status == Status::ok) {
                y = scale_.rate(dim, order == 1 ? s.qd[j] : s.qdd[j]);
              }
            }
            ys.push_back(y);
          }
          // An angle drawn as one continuous curve, at its file value's turn at the file's input.
          if (order == 0 && dim == Dimension::angle) {
            std::size_t first = 0;
            while (first < rows_.size() && rows_[first] != 0) ++first;
            ys = unwrap_degrees(ys, first);
          }
        }
        std::vector<std::string> legends;
        for (std::size_t j : members) {
          const Coordinate& q = system_.unknowns[j];
          legends.push_back("$" + to_latex(order == 0 ? q.symbol : order == 1 ? q.rate : q.second_rate) + "$");
        }
        axis(x_label, what + " [$\\mathrm{" + y_unit + "}$]", plotted++, curves, legends);
      }
    }
    if (!system_.points.empty()) {
      std::vector<std::vector<double>> curves;
      std::vector<std::string> legends;
      for (std::size_t p = 0; p < system_.points.size(); ++p) {
        std::vector<double>& ys = curves.emplace_back();
        for (std::size_t row : rows_)
          ys.push_back(row != kBreak && sweep_.status(row) == Status::ok ? sweep_.point(row, p).speed() / scale_.length : NAN);
        legends.push_back(latex_escape_text(system_.points[p].name));
      }
      axis(x_label, "speed [$\\mathrm{" + scale_.length_unit + "/s}$]", plotted++, curves, legends);
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
    std::string curves;
    double low[2] = {INFINITY, INFINITY}, high[2] = {-INFINITY, -INFINITY};
    for (std::size_t p : moving) {
      std::vector<double> coordinates;
      for (std::size_t row = 0; row < sweep_.size(); ++row)
        if (sweep_.status(row) != Status::unassembled)
          for (const int k : {0, 1}) coordinates.push_back(sweep_.point(row, p).position[k] / scale_.length);
      const double limit = plot_limit(coordinates);  // the point's own, one for x and y: the scales are equal
      curves += "\\addplot+[mark=none, thick] coordinates {";
      for (std::size_t row = 0; row < sweep_.size(); ++row) {
        const PointMotion m = sweep_.point(row, p);
        const double xy[2] = {m.position[0] / scale_.length, m.position[1] / scale_.length};
        const bool drawn = sweep_.status(row) != Status::unassembled && std::fabs(xy[0]) <= limit && std::fabs(xy[1]) <= limit;
        curves += drawn ? " (" + format_fixed(xy[0]) + "," + format_fixed(xy[1]) + ")" : std::string(" (nan,nan)");
        for (const int k : {0, 1}) {
          if (!drawn) continue;
          low[k] = std::min(low[k], xy[k]);
          high[k] = std::max(high[k], xy[k]);
        }
      }
      curves += " };\n\\addlegendentry{" + latex_escape_text(system_.points[p].name) + "}\n";
    }
    // Equal scales of a box far longer than high (paths along a line, one of them long) are
    // more than pgfplots can lay out: the short side is widened to 1/kPlotSpan of the long.
    std::string box;
    const double longest = std::max(high[0] - low[0], high[1] - low[1]);
    for (const int k : {0, 1}) {
      if (!(high[k] - low[k] < longest / kPlotSpan)) continue;
      const double middle = (low[k] + high[k]) / 2, half = longest / kPlotSpan / 2;
      const std::string axis = k == 0 ? "x" : "y";
      box += axis + "min=" + format_fixed(middle - half) + ", " + axis + "max=" + format_fixed(middle + half) + ", ";
    }
    const std::string l = "[$\\mathrm{" + scale_.length_unit + "}$]";
    out_ << "\\medskip\n\\noindent Paths of the points over the run (coupler curves of points on a coupler), "
            "to one scale in $x$ and $y$:\n" << kLatexFigureBegin << "\\begin{tikzpicture}\n\\begin{axis}[width=0.7\\linewidth, "
            "axis equal image, "
         << box << "xlabel={$x$ " << l << "}, ylabel={$y$ " << l
         << "}, unbounded coords=jump, legend style={font=\\footnotesize, at={(0.5,1.02)}, anchor=south, "
            "legend columns=-1}]\n"
         << curves << "\\end{axis}\n\\end{tikzpicture}\n" << latex_figure_caption("Paths of the points") << kLatexFigureEnd << "\n";
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
  // A turn's last row, a whole turn from the first, at 360 deg, not back at 0.
  double x_of(double si) const {
    if (!turn_) return scale_.input(si);
    const double x = wrapped(si);
    return x < 1e-9 && scale_.input(si) - scale_.input(sweep_.input(0)) >= 359.999 ? 360.0 : x;
  }

  // One axis of curves over rows_, each with its legend; a value past its curve's
  // plot_limit is a gap, as a non-finite one is.
  void axis(const std::string& x_label, const std::string& y_label, int index,
            const std::vector<std::vector<double>>& curves, const std::vector<std::string>& legends) {
    begin_axis(x_label, y_label, index);
    for (std::size_t k = 0; k < curves.size(); ++k) {
      // Each curve's own: pooled, a curve far larger than its neighbours (one of twenty)
      // was past the limit everywhere and vanished, and a small one kept its pole.
      const double limit = plot_limit(curves[k]);
      out_ << "\\addplot+[" << curve_style(k, rows_.size()) << "] coordinates {";
      for (std::size_t i = 0; i < rows_.size(); ++i) {
        const double y = curves[k][i];
        if (rows_[i] == kBreak || !(std::fabs(y) <= limit)) {
          out_ << (rows_[i] == kBreak ? " (nan,nan)" : " (" + format_fixed(x_of(sweep_.input(rows_[i]))) + ",nan)");
          continue;
        }
        out_ << " (" << format_fixed(x_of(sweep_.input(rows_[i]))) << "," << format_fixed(y) << ")";
      }
      out_ << " };\n\\addlegendentry{" << legends[k] << "}\n";
    }
    singular_marks();
    // Numbered, as every figure of the document: what is plotted against the input.
    std::string plotted;
    for (std::size_t k = 0; k < legends.size(); ++k) plotted += (k ? ", " : "") + legends[k];
    end_axis(plotted + " against $" + to_latex(system_.input.symbol) + "$");
  }

  // Curves told apart where they coincide: each its own dash pattern and marks, spaced
  // along it and set off from the other curves' (the legend shows both).
  static std::string curve_style(std::size_t k, std::size_t rows) {
    static const char* const dashes[] = {"solid", "dashed", "densely dotted", "dashdotted", "loosely dashed",
                                         "densely dashdotted"};
    static const char* const marks[] = {"*", "square*", "triangle*", "o", "square", "triangle"};
    const std::size_t every = std::max<std::size_t>(rows / 8, 1);
    return std::string("thick, ") + dashes[k % 6] + ", mark=" + marks[k % 6] + ", mark size=1.5pt, mark repeat=" +
           std::to_string(every) + ", mark phase=" + std::to_string(1 + (k * every / 3) % every) +
           ", mark options={solid}";
  }

  void begin_axis(const std::string& x_label, const std::string& y_label, int index) {
    // Each pair of plots a paragraph of its own, so that a page may break between pairs.
    out_ << (index % 2 ? "\\hfill" : index ? "\\par\\medskip\\noindent" : "\\par\\nopagebreak\\noindent") << "\\begin{minipage}{0.48\\linewidth}\n"
         << "\\begin{tikzpicture}\n\\begin{axis}[width=0.85\\linewidth, height=5.5cm, xlabel={" << x_label
         << "}, ylabel={" << y_label
         << "}, " << (turn_ ? "xmin=0, xmax=360, xtick={0,90,180,270,360}, " : "max space between ticks=40, ")
         << "ticklabel style={font=\\scriptsize}, "
         << "yticklabel style={/pgf/number format/fixed, /pgf/number format/precision=3}, "
         << "unbounded coords=jump, legend style={font=\\footnotesize, at={(0.5,1.02)}, anchor=south, "
         << "legend columns=-1}]\n";
  }
  void end_axis(const std::string& caption) {
    out_ << "\\end{axis}\n\\end{tikzpicture}\n" << latex_figure_caption(caption) << "\\end{minipage}\n";
  }

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
