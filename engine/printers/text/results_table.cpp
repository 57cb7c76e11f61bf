// Results for people: one block per input value (coordinates with rates and
// second rates, points with components and magnitudes).
#include <sstream>

#include "engine/printers/printer.hpp"
#include "engine/base/naming.hpp"
#include "engine/analysis/chain_instant.hpp"
#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/problem_scale.hpp"

namespace kinema {
namespace {

std::string pad(const std::string& text, std::size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

class ResultsTablePrinter : public ResultsPrinter {
 public:
  const char* name() const override { return "table"; }
  ViewNeeds needs(const PrintJob&) const override {
    ViewNeeds needs;
    needs.design_figures = true;  // the head's four-bar and slider lines
    return needs;
  }

  void head(std::string& text, const PrintJob& job, std::size_t) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    text += system.title + "\n";
    text += "units: angles deg, angular rates rad/s and rad/s^2, lengths " + scale.length_unit + ", velocities " +
            scale.length_unit + "/s, accelerations " + scale.length_unit + "/s^2\n";
    const Analysis& analysis = analysis_of(job);
    if (analysis.four_bar) text += "four-bar: " + describe_four_bar(*analysis.four_bar, system.input.name) + "\n";
    for (const Strokes& strokes : analysis.strokes)
      text += "slider: " + describe_strokes(strokes, system.input.name, scale.length_unit) + "\n";
  }

  void tail(std::string&, const PrintJob&, std::size_t) const override {}

  void rows(std::string& text, const PrintJob& job, const MotionTable& table, std::size_t first, std::size_t last,
            std::size_t) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    const Driver& input = system.input;
    const Dimension input_kind = input.dimension;
    const int digits = job.precision > 0 ? job.precision : 6;
    // The rows as the data formats print them (a value past the largest number in the
    // output unit is refused, not printed as inf), each value shown at its scale: zero at
    // the problem's scale and beside its column as 0 (row_scales).
    const std::size_t width = printed_column_count(job), results = result_column_count(system, table.is_circuit());
    const RowScales row_scales(system, result_columns(system, scale, table.is_circuit()));
    std::vector<double> checked(width * (last - first));
    printed_rows(job, table, first, last, checked.data());
    std::ostringstream out;
    for (std::size_t row = first; row < last; ++row) {
      const MotionState s = table[row];
      const double* values = checked.data() + (row - first) * width;
      const std::vector<double> scales = row_scales(values);
      const Shown number{values, scales.data(), digits};
      out << "\n" << input.name << " = " << number(0) << " " << scale.coordinate_unit(input_kind) << "   "
          << input.rate.get_name() << " = " << number(1) << " " << scale.rate_unit(input_kind) << "   "
          << input.second_rate.get_name() << " = " << number(2) << " " << scale.second_rate_unit(input_kind) << "\n";
      const std::string message = describe_failure(system, s);
      if (s.status == Status::unassembled) {
        out << "  not assembled: " << message << "\n";
        continue;
      }
      if (s.status == Status::singular) out << "  SINGULAR: " << message << "\n";
      else if (!message.empty()) out << "  note: " << message << "\n";
      if (table.is_circuit()) {
        out << "  branch:";
        const std::vector<std::string> joints = dyad_inner_joints(system);
        for (std::size_t k = 0; k < joints.size(); ++k)
          out << " " << joints[k] << (table.assembly_sign(row, k) > 0 ? " +1" : " -1");
        out << " (each dyad's assembly sign, by its inner joint)\n";
      }
      out << "  " << pad("coordinate", 12) << pad("value", 16) << pad("rate", 26) << "second rate\n";
      for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
        const Coordinate& q = system.unknowns[i];
        const std::size_t at = kInputColumns + 3 * i;
        out << "  " << pad(q.name, 12) << pad(number(at) + " " + scale.coordinate_unit(q.dimension), 16);
        if (s.status == Status::ok) {
          out << pad(q.rate.get_name() + " = " + number(at + 1) + " " + scale.rate_unit(q.dimension), 26)
              << q.second_rate.get_name() << " = " << number(at + 2) << " " << scale.second_rate_unit(q.dimension);
        } else {
          out << "undefined (singular)";
        }
        out << "\n";
      }
      if (s.status != Status::ok) continue;
      std::size_t at = kInputColumns + 3 * system.unknowns.size();
      if (!system.points.empty()) at = print_points(out, system, number, at);
      if (!system.frames.empty()) print_frames(out, system, number, at);
      if (system.plan) print_sliders(out, system, scale, number, linkage_columns_begin(system));
      if (job.sensitivities) {
        out << "  " << pad("sensitivity", 24) << "value (the column's unit per the parameter's)\n";
        // Shown with the sensitivities of the same unit: those of other units are other quantities.
        const auto& sensitivities = *job.sensitivities;
        for (std::size_t k = 0; k < sensitivities.size(); ++k) {
          double with = 0;
          for (std::size_t j = 0; j < sensitivities.size(); ++j)
            if (sensitivities[j].named.unit == sensitivities[k].named.unit)
              with = std::max(with, largest_magnitude({values[results + j]}));
          out << "  " << pad(sensitivities[k].named.name, 24) << format_at_scale(values[results + k], with, digits) << " "
              << sensitivities[k].named.unit << "\n";
        }
      }
    }
    text += out.str();
  }

 private:
  // Value k of a printed row at its scale (row_scales), in the table's digits.
  struct Shown {
    const double* values;
    const double* scales;
    int digits;
    std::string operator()(std::size_t k) const { return format_at_scale(values[k], scales[k], digits); }
  };

  // Joints and links: slider blocks (turning with their guides), and at each slider its
  // relative velocity and acceleration along the line and the Coriolis acceleration; the
  // row's values from `at` on.
  static void print_sliders(std::ostream& out, const ConstraintSystem& system, const OutputScale& scale,
                            const Shown& number, std::size_t at) {
    const auto blocks = block_links(system);
    if (!blocks.empty()) out << "  " << pad("block", 8) << pad("angle", 26) << pad("rate", 26) << "second rate\n";
    for (const auto& [body, angle] : blocks) {
      out << "  " << pad(system.plan->links[body - 1].name, 8) << pad(angle + " = " + number(at) + " deg", 26)
          << pad(default_rate_name(angle, 1) + " = " + number(at + 1) + " rad/s", 26) << default_rate_name(angle, 2)
          << " = " << number(at + 2) << " rad/s^2\n";
      at += 3;
    }
    const auto& sliders = system.plan->sliders;
    if (sliders.empty()) return;
    const std::string& l = scale.length_unit;
    const auto pair = [&](std::size_t k) { return "(" + number(k) + ", " + number(k + 1) + ")"; };
    out << "  " << pad("slider", 8) << pad("v_rel (" + l + "/s)", 26) << pad("a_rel (" + l + "/s^2)", 26)
        << "Coriolis 2 w x v_rel (" << l << "/s^2)\n";
    for (const SolvingPlan::Slider& slider : sliders) {
      out << "  " << pad(system.plan->joints[slider.joint].name, 8) << pad(pair(at), 26) << pad(pair(at + 2), 26)
          << pair(at + 4) << "\n";
      at += 6;
    }
    const auto guides = guide_points(system);
    if (!guides.empty()) {
      out << "  " << pad("guide", 8) << pad("v (" + l + "/s)", 26) << "a (" << l << "/s^2)   (the guide's point under the slider)\n";
      for (const GuidePoint& g : guides) {
        out << "  " << pad(g.name, 8) << pad(pair(at), 26) << pair(at + 2) << "\n";
        at += 4;
      }
    }
    const auto turnings = relative_turnings(system);
    if (!turnings.empty()) {
      out << "  " << pad("links", 8) << pad("relative rate", 30) << "relative second rate\n";
      for (const RelativeTurning& r : turnings) {
        out << "  " << pad(system.plan->links[r.block - 1].name + "/" + system.plan->links[r.other - 1].name, 8)
            << pad(r.rate_name + " = " + number(at) + " rad/s", 30) << r.second_rate_name << " = " << number(at + 1)
            << " rad/s^2\n";
        at += 2;
      }
    }
  }

  // Spatial chains: each frame's angular velocity and acceleration relative to the observer.
  static void print_frames(std::ostream& out, const ConstraintSystem& system, const Shown& number, std::size_t at) {
    const auto triple = [&](std::size_t k) { return "(" + number(k) + ", " + number(k + 1) + ", " + number(k + 2) + ")"; };
    out << "  " << pad("frame", 8) << pad("w relative to " + chain_observer(system) + " (rad/s)", 40)
        << "alpha (rad/s^2)\n";
    for (std::size_t f = 0; f < system.frames.size(); ++f, at += 6)
      out << "  " << pad(system.frames[f].name, 8) << pad(triple(at), 40) << triple(at + 3) << "\n";
  }

  // One header per run of points with the same components; returns where the row's values
  // after the points begin.
  static std::size_t print_points(std::ostream& out, const ConstraintSystem& system, const Shown& number, std::size_t at) {
    const std::vector<std::string>* header = nullptr;
    for (std::size_t p = 0; p < system.points.size(); ++p) {
      const PointObservable& point = system.points[p];
      if (!header || *header != point.components) {
        header = &point.components;
        out << "  " << pad("point", 8);
        for (const auto& c : point.components) out << pad(c, 12);
        for (const auto& c : point.components) out << pad("v" + c, 12);
        out << pad("|v|", 12);
        for (const auto& c : point.components) out << pad("a" + c, 12);
        out << "|a|\n";
      }
      // Position, velocity, speed, acceleration, its magnitude: the row's order.
      const std::size_t values = 3 * point.components.size() + 2;
      out << "  " << pad(point.name, 8);
      for (std::size_t k = 0; k + 1 < values; ++k) out << pad(number(at + k), 12);
      out << number(at + values - 1) << "\n";
      at += values;
    }
    return at;
  }
};

}  // namespace

const ResultsPrinter& results_table_printer() {
  static const ResultsTablePrinter printer;
  return printer;
}

}  // namespace kinema
