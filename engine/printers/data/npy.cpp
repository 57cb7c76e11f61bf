// Results for data tools: a NumPy structured array (.npy, format 1.0 or 2.0), one
// record per input value and one named little-endian float64 field per CSV column
// ("theta3", "omega3", "P_vx", ...), in the same output units; NaN where a value is
// undefined; "status" as a 0/1/2 code (ok, singular, unassembled) and
// "resumed_after_gap" as a bool. numpy.load and pandas read it without a parser.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "engine/printers/data/npy_header.hpp"
#include "engine/printers/printer.hpp"
#include "engine/analysis/output_scale.hpp"

namespace kinema {
namespace {

// The fields: the CSV's columns without their units, then the two flags.
std::vector<NpyField> npy_fields(const std::vector<std::string>& names) {
  std::vector<NpyField> fields;
  for (const std::string& name : names) fields.push_back({name, "<f8"});
  // The two flags' names, unless the file took them (field names must differ).
  std::string status = "status", gap = "resumed_after_gap";
  for (std::string* flag : {&status, &gap})
    while (std::find(names.begin(), names.end(), *flag) != names.end()) *flag += "_";
  fields.push_back({status, "|u1"});
  fields.push_back({gap, "|b1"});
  return fields;
}

class NpyPrinter : public ResultsPrinter {
 public:
  const char* name() const override { return "npy"; }

  void head(std::string& out, const PrintJob& job, std::size_t rows) const override {
    std::vector<std::string> names;  // the CSV's column names without their units
    for (const ResultColumn& column : printed_columns(job)) names.push_back(column.name);
    out += npy_header(npy_fields(names), rows);
  }

  void rows(std::string& out, const PrintJob& job, const MotionTable& table, std::size_t first, std::size_t last,
            std::size_t) const override {
    // The block's values at once (worked out column by column), then a record a row.
    const std::size_t columns = printed_column_count(job);
    std::vector<double> values((last - first) * columns);
    printed_rows(job, table, first, last, values.data());
    const std::size_t bytes = columns * sizeof(double);
    std::vector<char> record(bytes + 2);
    out.reserve(out.size() + (last - first) * record.size());  // one allocation a block
    for (std::size_t row = first; row < last; ++row) {
      // x86-64 and every platform kinema builds on are little-endian, as '<f8' says.
      std::memcpy(record.data(), values.data() + (row - first) * columns, bytes);
      const Status status = table.status(row);
      record[bytes] = static_cast<char>(status == Status::ok ? 0 : status == Status::singular ? 1 : 2);
      record[bytes + 1] = static_cast<char>(table.failure(row).kind == Failure::Kind::resumed_after_gap ? 1 : 0);
      out.append(record.data(), record.size());
    }
  }

  void tail(std::string&, const PrintJob&, std::size_t) const override {}
};

}  // namespace

const ResultsPrinter& npy_printer() {
  static const NpyPrinter printer;
  return printer;
}

}  // namespace kinema
