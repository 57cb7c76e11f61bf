// Results for spreadsheets: one row per input value, each column named with
// its unit in the header ("theta3 [deg]", "P_vx [mm/s]"), a status column, and
// empty cells where a value is undefined, and a note column (resumed_after_gap).
#include <kinema/engine/printers/printer.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/output_scale.hpp>

namespace kinema {
namespace {

class CsvPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::results; }
  const char* name() const override { return "csv"; }

  void print(std::ostream& out, const PrintJob& job) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    const Driver& input = system.input;
    const Dimension input_kind = input.dimension;
    const int digits = job.precision > 0 ? job.precision : 12;
    auto number = [&](double value) { return format_significant(value, digits); };
    const std::vector<ResultColumn> columns = result_columns(system, scale);
    for (std::size_t k = 0; k < columns.size(); ++k) {
      out << (k == 0 ? "" : ",") << columns[k].name << " [" << columns[k].unit << "]";
      if (k + 1 == kInputColumns) out << ",status";
    }
    const std::size_t point_columns = columns.size() - kInputColumns - 3 * system.unknowns.size();
    // A last column says what a status cannot: this row was reached after a gap, so
    // its assembly branch is not guaranteed to be the one of the rows before it.
    out << ",note\n";
    for (const MotionState& s : *job.values) {
      const char* note = s.failure.kind == Failure::Kind::resumed_after_gap ? "resumed_after_gap" : "";
      out << number(scale.input(s.input)) << "," << number(scale.rate(input_kind, s.input_rate)) << ","
          << number(scale.rate(input_kind, s.input_second_rate)) << "," << status_name(s.status);
      for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
        const Dimension kind = system.unknowns[i].dimension;
        out << ",";
        if (s.status != Status::unassembled) out << number(scale.coordinate(kind, s.q[i]));
        out << ",";
        if (s.status == Status::ok) out << number(scale.rate(kind, s.qd[i]));
        out << ",";
        if (s.status == Status::ok) out << number(scale.rate(kind, s.qdd[i]));
      }
      if (s.status != Status::ok) {
        out << std::string(point_columns, ',') << "," << note << "\n";
        continue;
      }
      const double f = scale.length;
      for (const PointMotion& m : s.points) {
        for (std::size_t c = 0; c < m.dimension; ++c) out << "," << number(m.position[c] / f);
        for (std::size_t c = 0; c < m.dimension; ++c) out << "," << number(m.velocity[c] / f);
        out << "," << number(m.speed() / f);
        for (std::size_t c = 0; c < m.dimension; ++c) out << "," << number(m.acceleration[c] / f);
        out << "," << number(m.acceleration_magnitude() / f);
      }
      out << "," << note << "\n";
    }
  }
};

}  // namespace

const Printer& csv_printer() {
  static const CsvPrinter printer;
  return printer;
}

}  // namespace kinema
