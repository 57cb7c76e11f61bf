// Results for data tools: a NumPy structured array (.npy, format 1.0 or 2.0), one
// record per input value and one named little-endian float64 field per CSV column
// ("theta3", "omega3", "P_vx", ...), in the same output units; NaN where a value is
// undefined; "status" as a 0/1/2 code (ok, singular, unassembled) and
// "resumed_after_gap" as a bool. numpy.load and pandas read it without a parser.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "engine/printers/printer.hpp"
#include "engine/analysis/output_scale.hpp"

namespace kinema {
namespace {

// The header: magic, version, length, then a Python dict literal padded with spaces
// (and a final newline) so that the data starts on a 64-byte boundary.
std::string npy_header(const std::vector<std::string>& names, std::size_t rows) {
  std::string descr = "[";
  for (const std::string& name : names) descr += "('" + name + "', '<f8'), ";
  // The two flags' names, unless the file took them (field names must differ).
  std::string status = "status", gap = "resumed_after_gap";
  for (std::string* flag : {&status, &gap})
    while (std::find(names.begin(), names.end(), *flag) != names.end()) *flag += "_";
  descr += "('" + status + "', '|u1'), ('" + gap + "', '|b1')]";
  std::string dict = "{'descr': " + descr + ", 'fortran_order': False, 'shape': (" + std::to_string(rows) + ",), }";
  const bool version1 = dict.size() + 12 < 65000;
  const std::size_t prefix = version1 ? 10 : 12;  // magic 6 + version 2 + length 2 or 4
  const std::size_t total = (prefix + dict.size() + 1 + 63) / 64 * 64;
  dict += std::string(total - prefix - dict.size() - 1, ' ') + "\n";
  std::string header = "\x93NUMPY";
  header += version1 ? '\x01' : '\x02';
  header += '\x00';
  const std::uint32_t length = static_cast<std::uint32_t>(dict.size());
  for (std::size_t b = 0; b < (version1 ? 2u : 4u); ++b) header += static_cast<char>((length >> (8 * b)) & 0xff);
  return header + dict;
}

class NpyPrinter : public ResultsPrinter {
 public:
  const char* name() const override { return "npy"; }

  void head(std::string& out, const PrintJob& job, std::size_t rows) const override {
    std::vector<std::string> names;  // the CSV's column names without their units
    for (const ResultColumn& column : printed_columns(job)) names.push_back(column.name);
    out += npy_header(names, rows);
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
