// Results for spreadsheets: one row per input value, each column named with
// its unit in the header ("theta3 [deg]", "P_vx [mm/s]"), a status column,
// empty cells where a value is undefined, and a note column (resumed_after_gap).
#include <cmath>
#include <vector>

#include <kinema/engine/printers/printer.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/output_scale.hpp>

namespace kinema {
namespace {

class CsvPrinter : public ResultsPrinter {
 public:
  const char* name() const override { return "csv"; }

  void head(std::string& out, const PrintJob& job, std::size_t) const override {
    const ConstraintSystem& system = job.model.system;
    const std::vector<ResultColumn> columns = result_columns(system, OutputScale(system), job.circuit);
    for (std::size_t k = 0; k < columns.size(); ++k) {
      out += (k == 0 ? "" : ",") + columns[k].name + " [" + columns[k].unit + "]";
      if (k + 1 == kInputColumns) out += ",status";
    }
    // A last column says what a status cannot: this row was reached after a gap, so
    // its assembly branch is not guaranteed to be the one of the rows before it.
    out += ",note\n";
  }

  void rows(std::string& out, const PrintJob& job, const MotionTable& table, std::size_t first, std::size_t last,
            std::size_t) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    const int digits = job.precision > 0 ? job.precision : 12;
    std::vector<double> values(result_columns(system, scale, job.circuit).size());
    std::vector<char> line((kMaxNumberChars + 1) * values.size() + 64);
    // Room for a typical block at once: growing by doubling copies the text and, in
    // fresh pages, costs more than formatting it.
    out.reserve(out.size() + (last - first) * (values.size() * std::size_t(digits + 7) + 24));
    for (std::size_t row = first; row < last; ++row) {
      result_values(system, scale, table, row, values.data());
      // The input's columns, the status, then the rest; undefined values (NaN) empty.
      char* p = put_significant_list(line.data(), values.data(), kInputColumns, digits, ',');
      *p++ = ',';
      for (const char* s = status_name(table.status(row)); *s; ++s) *p++ = *s;
      if (values.size() > kInputColumns) {
        *p++ = ',';
        p = put_significant_list(p, values.data() + kInputColumns, values.size() - kInputColumns, digits, ',');
      }
      out.append(line.data(), p);
      out += table.failure(row).kind == Failure::Kind::resumed_after_gap ? ",resumed_after_gap\n" : ",\n";
    }
  }

  void tail(std::string&, const PrintJob&, std::size_t) const override {}
};

}  // namespace

const ResultsPrinter& csv_printer() {
  static const CsvPrinter printer;
  return printer;
}

}  // namespace kinema
