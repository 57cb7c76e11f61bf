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
    auto column = [](const std::string& name, const std::string& unit) { return name + " [" + unit + "]"; };
    const int digits = job.precision > 0 ? job.precision : 12;
    auto number = [&](double value) { return format_significant(value, digits); };
    out << column(input.name, scale.coordinate_unit(input_kind)) << ","
        << column(input.rate.get_name(), scale.rate_unit(input_kind)) << ","
        << column(input.second_rate.get_name(), scale.second_rate_unit(input_kind)) << ",status";
    for (const Coordinate& q : system.unknowns) {
      out << "," << column(q.name, scale.coordinate_unit(q.dimension)) << ","
          << column(q.rate.get_name(), scale.rate_unit(q.dimension)) << ","
          << column(q.second_rate.get_name(), scale.second_rate_unit(q.dimension));
    }
    const std::string l = scale.length_unit;
    std::size_t point_columns = 0;
    for (const PointObservable& p : system.points) {
      for (const auto& c : p.components) out << "," << column(p.name + "_" + c, l);
      for (const auto& c : p.components) out << "," << column(p.name + "_v" + c, l + "/s");
      out << "," << column(p.name + "_speed", l + "/s");
      for (const auto& c : p.components) out << "," << column(p.name + "_a" + c, l + "/s^2");
      out << "," << column(p.name + "_acceleration", l + "/s^2");
      point_columns += 3 * p.components.size() + 2;
    }
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
