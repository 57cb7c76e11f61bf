#include "engine/printers/latex/pgfplots.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/printers/latex/label_boxes.hpp"
#include "engine/printers/latex/latex_format.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/plot_range.hpp"

namespace kinema {
namespace {

// A value more than this many times the typical size of its plot's values is drawn as a
// gap: a pole (a point at a*tan(theta2) is 1.6e16 a at 90 deg) would squash every other
// value of the plot flat, and pgfplots stops ("divide by 0.0", "Dimension too large") on
// values some 1e6 times apart in the paths' equal scales.
constexpr double kPlotSpan = 1000;
// The paths' box past their extent on each side, as a fraction of its longer side.
constexpr double kPathMargin = 0.04;

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

// A plot's axis in cm (scale only axis): two to a text width's row with their tick labels
// and axis labels beside them.
constexpr double kAxisWidthCm = 5.4, kAxisHeightCm = 4.0;

// One axis's limits and ticks (`axis` x or y) over [lo, hi] drawn `length_cm` long: the
// smallest round step (1, 2, 2.5 or 5 times a power of ten) at which neighbouring tick
// labels (\scriptsize, as label_box estimates them) stand apart with a gap, side by side
// on x, one above the other on y; written with their labels, so that pgfplots neither
// picks other ticks nor scales them.
// Where `exponent` is given and the values reach 10^5, the labels count in 10^exponent
// (a multiple of 3, set there for the axis's label): "-2000000" was too long to read.
std::string axis_ticks(char axis, double lo, double hi, double length_cm, bool degrees_turn = false, int* exponent = nullptr) {
  if (!(hi - lo > 1e-6 * std::max(std::fabs(lo), std::fabs(hi)))) {  // a constant (to round-off): a tenth round it, 0 in -1..1
    const double pad = std::max(std::fabs(lo) * 0.1, lo == 0 ? 1.0 : 1e-6);
    lo -= pad;
    hi += pad;
  }
  const double per_cm = (hi - lo) / length_cm;
  const double largest = std::max(std::fabs(lo), std::fabs(hi));
  const int power = exponent && largest >= 1e5 ? 3 * static_cast<int>(std::floor(std::log10(largest) / 3)) : 0;
  if (exponent) *exponent = power;
  const double unit = std::pow(10.0, power);
  std::vector<double> ticks;
  std::vector<std::string> labels;
  int decimals = 0;
  // A turn's degrees at 45, 90 or 180 deg, else the round steps from a thousandth of the range up.
  const std::vector<double> mantissas = degrees_turn ? std::vector<double>{45, 90, 180} : std::vector<double>{1, 2, 2.5, 5};
  for (double decade = degrees_turn ? 1 : std::pow(10.0, std::floor(std::log10(hi - lo)) - 3);; decade *= 10) {
    bool fits = false;
    for (double mantissa : mantissas) {
      const double step = mantissa * decade;
      decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)) + (mantissa == 2.5 ? 1 : 0));
      const int label_decimals =
          std::max(0, static_cast<int>(std::ceil(-std::log10(step / unit) - 1e-9)) + (mantissa == 2.5 ? 1 : 0));
      ticks.clear();
      labels.clear();
      for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; ++k) {
        ticks.push_back(k == 0 ? 0.0 : k * step);  // not -0
        labels.push_back("$" + format_fixed(ticks.back() / unit, label_decimals) + "$");
      }
      fits = true;
      for (std::size_t i = 1; i < ticks.size() && fits; ++i) {
        const LabelBox a = label_box(labels[i - 1], 8, 0), b = label_box(labels[i], 8, 0);
        const double room = axis == 'x' ? a.half_width + b.half_width : a.half_height + b.half_height;
        fits = (ticks[i] - ticks[i - 1]) / per_cm >= room + 0.25;
      }
      // Not more ticks than a reader needs: 1 cm apart at least across, 0.8 cm up.
      fits = fits && (ticks.size() < 2 || step / per_cm >= (axis == 'x' ? 1.0 : 0.8));
      if (fits) break;
    }
    if (fits) break;
  }
  // The limits to a hundredth of a step, the ticks as their labels.
  std::string out = std::string(1, axis) + "min=" + format_fixed(lo, decimals + 2) + ", " + axis +
                    "max=" + format_fixed(hi, decimals + 2) + ", " + axis + "tick={";
  for (std::size_t i = 0; i < ticks.size(); ++i) out += (i ? "," : "") + format_fixed(ticks[i], decimals);
  out += "}, " + std::string(1, axis) + "ticklabels={";
  for (std::size_t i = 0; i < labels.size(); ++i) out += (i ? "," : "") + labels[i];
  return out + "}, ";
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
        axis(x_label, what, y_unit, plotted++, curves, legends);
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
      axis(x_label, "speed", scale_.length_unit + "/s", plotted++, curves, legends);
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
    const double longest = std::max(high[0] - low[0], high[1] - low[1]);
    for (const int k : {0, 1}) {
      if (!(high[k] - low[k] < longest / kPlotSpan)) continue;
      const double middle = (low[k] + high[k]) / 2, half = longest / kPlotSpan / 2;
      low[k] = middle - half;
      high[k] = middle + half;
    }
    // A margin round the paths: a path on the box's edge (a slider's, along its guide) was
    // drawn on the axis's frame and could not be seen.
    for (const int k : {0, 1}) {
      low[k] -= kPathMargin * longest;
      high[k] += kPathMargin * longest;
    }
    // One scale for x and y, the box at most 11 cm wide and 5.5 cm high (a page's last
    // third); its ticks chosen for those lengths.
    const double cm = std::min(11.0 / (high[0] - low[0]), 5.5 / (high[1] - low[1]));
    const double width = (high[0] - low[0]) * cm, height = (high[1] - low[1]) * cm;
    const std::string l = "[$\\mathrm{" + scale_.length_unit + "}$]";
    out_ << "\\medskip\n\\noindent Paths of the points over the run (coupler curves of points on a coupler), "
            "to one scale in $x$ and $y$:\n" << kLatexFigureBegin << "\\begin{tikzpicture}\n\\begin{axis}[axis equal image, "
            "scale only axis, width="
         << format_fixed(width, 3) << "cm, height=" << format_fixed(height, 3) << "cm, "
         << axis_ticks('x', low[0], high[0], width) << axis_ticks('y', low[1], high[1], height)
         << "scaled ticks=false, ticklabel style={font=\\scriptsize}, xlabel={$x$ " << l << "}, ylabel={$y$ " << l
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
  void axis(const std::string& x_label, const std::string& y_name, const std::string& y_unit, int index,
            const std::vector<std::vector<double>>& curves, const std::vector<std::string>& legends) {
    // Each curve's own: pooled, a curve far larger than its neighbours (one of twenty)
    // was past the limit everywhere and vanished, and a small one kept its pole.
    std::vector<double> limits;
    for (const std::vector<double>& ys : curves) limits.push_back(plot_limit(ys));
    // The axis's ranges: the rows' inputs (a turn's 0 to 360 deg) and the values drawn.
    double x_lo = turn_ ? 0 : INFINITY, x_hi = turn_ ? 360 : -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      if (rows_[i] == kBreak) continue;
      x_lo = std::min(x_lo, x_of(sweep_.input(rows_[i])));
      x_hi = std::max(x_hi, x_of(sweep_.input(rows_[i])));
      for (std::size_t k = 0; k < curves.size(); ++k)
        if (std::fabs(curves[k][i]) <= limits[k]) {
          const double y = std::round(curves[k][i] * 1e6) / 1e6;  // as written (format_fixed): round-off is 0
          y_lo = std::min(y_lo, y);
          y_hi = std::max(y_hi, y);
        }
    }
    if (!std::isfinite(y_lo)) y_lo = y_hi = 0;  // nothing drawn
    const double margin = (y_hi - y_lo) * 0.05;  // the curves off the frame
    int exponent = 0;
    const std::string ticks =
        axis_ticks('x', x_lo, x_hi, kAxisWidthCm, turn_) + axis_ticks('y', y_lo - margin, y_hi + margin, kAxisHeightCm, false, &exponent);
    const std::string in_powers = exponent ? "10^{" + std::to_string(exponent) + "}\\," : "";
    begin_axis(x_label, y_name + " [$" + in_powers + "\\mathrm{" + y_unit + "}$]", index, ticks);
    for (std::size_t k = 0; k < curves.size(); ++k) {
      const double limit = limits[k];
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

  void begin_axis(const std::string& x_label, const std::string& y_label, int index, const std::string& ticks) {
    // Each pair of plots a paragraph of its own, so that a page may break between pairs.
    out_ << (index % 2 ? "\\hfill" : index ? "\\par\\medskip\\noindent" : "\\par\\nopagebreak\\noindent") << "\\begin{minipage}{0.48\\linewidth}\n"
         << "\\begin{tikzpicture}\n\\begin{axis}[scale only axis, width=" << format_fixed(kAxisWidthCm, 1)
         << "cm, height=" << format_fixed(kAxisHeightCm, 1) << "cm, xlabel={" << x_label << "}, ylabel={" << y_label
         << "}, " << ticks << "scaled ticks=false, ticklabel style={font=\\scriptsize}, "
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
