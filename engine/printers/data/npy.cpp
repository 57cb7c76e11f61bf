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

#include <kinema/engine/printers/printer.hpp>
#include <kinema/engine/report/output_scale.hpp>

namespace kinema {
namespace {

constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();

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

void put(std::string& out, double value) {
  char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);  // x86-64 and every platform kinema builds on: little-endian
  out.append(bytes, sizeof value);
}

class NpyPrinter : public Printer {
 public:
  PrintKind kind() const override { return PrintKind::results; }
  const char* name() const override { return "npy"; }

  void print(std::ostream& out, const PrintJob& job) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    const Dimension input_kind = system.input.dimension;
    std::vector<std::string> names;  // the CSV's column names without their units
    for (const ResultColumn& column : result_columns(system, scale)) names.push_back(column.name);
    std::string data = npy_header(names, job.values->size());
    const std::size_t record = names.size() * sizeof(double) + 2;
    data.reserve(data.size() + record * job.values->size());
    for (const MotionState& s : *job.values) {
      put(data, scale.input(s.input));
      put(data, scale.rate(input_kind, s.input_rate));
      put(data, scale.rate(input_kind, s.input_second_rate));
      for (std::size_t i = 0; i < system.unknowns.size(); ++i) {
        const Dimension kind = system.unknowns[i].dimension;
        put(data, s.status != Status::unassembled ? scale.coordinate(kind, s.q[i]) : kUndefined);
        put(data, s.status == Status::ok ? scale.rate(kind, s.qd[i]) : kUndefined);
        put(data, s.status == Status::ok ? scale.rate(kind, s.qdd[i]) : kUndefined);
      }
      const double f = scale.length;
      for (std::size_t p = 0; p < system.points.size(); ++p) {
        const std::size_t dimension = system.points[p].components.size();
        const bool ok = s.status == Status::ok;
        const PointMotion* m = ok ? &s.points[p] : nullptr;
        for (std::size_t c = 0; c < dimension; ++c) put(data, ok ? m->position[c] / f : kUndefined);
        for (std::size_t c = 0; c < dimension; ++c) put(data, ok ? m->velocity[c] / f : kUndefined);
        put(data, ok ? m->speed() / f : kUndefined);
        for (std::size_t c = 0; c < dimension; ++c) put(data, ok ? m->acceleration[c] / f : kUndefined);
        put(data, ok ? m->acceleration_magnitude() / f : kUndefined);
      }
      data += static_cast<char>(s.status == Status::ok ? 0 : s.status == Status::singular ? 1 : 2);
      data += static_cast<char>(s.failure.kind == Failure::Kind::resumed_after_gap ? 1 : 0);
    }
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
  }
};

}  // namespace

const Printer& npy_printer() {
  static const NpyPrinter printer;
  return printer;
}

}  // namespace kinema
