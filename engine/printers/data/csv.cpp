// Results for spreadsheets: one row per input value, each column named with
// its unit in the header ("theta3 [deg]", "P_vx [mm/s]"), a status column,
// empty cells where a value is undefined, and a note column (resumed_after_gap).
#include <algorithm>
#include <cmath>
#include <vector>

#include "engine/printers/printer.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"

namespace kinema {
namespace {

class CsvPrinter : public ResultsPrinter {
 public:
  const char* name() const override { return "csv"; }

  void head(std::string& out, const PrintJob& job, std::size_t) const override {
    const std::vector<ResultColumn> columns = printed_columns(job);
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
    const int digits = job.precision > 0 ? job.precision : 12;
    const std::size_t columns = printed_column_count(job), rows = last - first,
                      block_values = columns * rows;
    // The values and at most kMaxNumberChars + 1 characters a value, the status and the
    // note a row, in buffers of the thread's that only grow (a new or resized buffer would
    // be cleared first, every block).
    thread_local std::vector<double> values;
    values.resize(std::max(values.size(), block_values));
    printed_rows(job, table, first, last, values.data());
    thread_local std::vector<char> text;
    text.resize(std::max(text.size(), rows * ((kMaxNumberChars + 1) * columns + 64)));
    char* p = text.data();
    const auto put_text = [&p](const char* text) {
      while (*text) *p++ = *text++;
    };
    // The values of the block in chunks, whatever the rows: a row's columns are the input's,
    // the status, the rest (undefined ones empty), then the note.
    std::size_t row = first, column = 0;
    SignificantChunk chunk;
    const bool chunked = SignificantChunk::handles(digits);
    for (std::size_t begin = 0; begin < block_values; begin += SignificantChunk::capacity) {
      const std::size_t n = std::min(SignificantChunk::capacity, block_values - begin);
      if (chunked) chunk.convert(values.data() + begin, n, digits);
      for (std::size_t k = 0; k < n;) {
        // The run of values up to the status or the end of the row, within this chunk.
        const std::size_t run_end = column < kInputColumns ? kInputColumns : columns;
        const std::size_t count = std::min(run_end - column, n - k);
        if (column > 0) *p++ = ',';
        p = chunked ? chunk.put(p, k, k + count, ',') : put_significant_list(p, values.data() + begin + k, count, digits, ',');
        k += count;
        column += count;
        if (column == kInputColumns) {
          *p++ = ',';
          put_text(status_name(table.status(row)));
        }
        if (column == columns) {
          put_text(table.failure(row).kind == Failure::Kind::resumed_after_gap ? ",resumed_after_gap\n" : ",\n");
          ++row;
          column = 0;
        }
      }
    }
    out.append(text.data(), p);
  }

  void tail(std::string&, const PrintJob&, std::size_t) const override {}
};

}  // namespace

const ResultsPrinter& csv_printer() {
  static const CsvPrinter printer;
  return printer;
}

}  // namespace kinema
