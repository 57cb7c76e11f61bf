#include "engine/printers/data/study_table.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/printers/data/npy_header.hpp"

namespace kinema {

namespace {

std::size_t row_count(const std::vector<StudyColumn>& columns) {
  return columns.empty() ? 0 : columns.front().values.size();
}

std::string csv_table(const std::vector<StudyColumn>& columns, int precision) {
  std::string out;
  for (std::size_t k = 0; k < columns.size(); ++k)
    out += (k ? "," : "") + columns[k].name + (columns[k].unit.empty() ? "" : " [" + columns[k].unit + "]");
  out += "\n";
  for (std::size_t row = 0; row < row_count(columns); ++row) {
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const StudyColumn& c = columns[k];
      const double v = c.values[row];
      if (k) out += ",";
      if (c.kind == StudyColumn::Kind::grashof) out += grashof_name(static_cast<GrashofClass>(v));
      else if (c.kind == StudyColumn::Kind::flag) out += v != 0 ? "true" : "false";
      else if (std::isfinite(v)) out += format_significant(v, precision > 0 ? precision : 12);
    }
    out += "\n";
  }
  return out;
}

std::string json_table(const std::vector<StudyColumn>& columns, int precision) {
  using json = nlohmann::ordered_json;
  json units = json::object(), designs = json::array();
  for (const StudyColumn& c : columns)
    if (!c.unit.empty()) units[c.name] = c.unit;
  for (std::size_t row = 0; row < row_count(columns); ++row) {
    json design = json::object();
    for (const StudyColumn& c : columns) {
      const double v = c.values[row];
      if (c.kind == StudyColumn::Kind::grashof) design[c.name] = grashof_name(static_cast<GrashofClass>(v));
      else if (c.kind == StudyColumn::Kind::flag) design[c.name] = v != 0;
      else if (c.kind == StudyColumn::Kind::count) design[c.name] = static_cast<std::uint64_t>(v);
      else if (!std::isfinite(v)) design[c.name] = nullptr;
      else design[c.name] = precision > 0 ? round_significant(v, precision) : v;
    }
    designs.push_back(std::move(design));
  }
  return json{{"units", units}, {"designs", designs}}.dump(2) + "\n";
}

// The npy type of a column's field and its size.
const char* npy_type(StudyColumn::Kind kind) {
  switch (kind) {
    case StudyColumn::Kind::grashof: return "|i1";
    case StudyColumn::Kind::flag: return "|b1";
    case StudyColumn::Kind::count: return "<u4";
    case StudyColumn::Kind::real: break;
  }
  return "<f8";
}
std::size_t npy_size(StudyColumn::Kind kind) {
  return kind == StudyColumn::Kind::real ? 8 : kind == StudyColumn::Kind::count ? 4 : 1;
}

std::string npy_table(const std::vector<StudyColumn>& columns) {
  std::vector<NpyField> fields;
  for (const StudyColumn& c : columns) fields.push_back({c.name, npy_type(c.kind)});
  const std::size_t rows = row_count(columns);
  std::string out = npy_header(fields, rows);
  for (std::size_t row = 0; row < rows; ++row) {
    for (const StudyColumn& c : columns) {  // little-endian, as the types say
      const double v = c.values[row];
      char bytes[8];
      if (c.kind == StudyColumn::Kind::real) {
        std::memcpy(bytes, &v, 8);
      } else if (c.kind == StudyColumn::Kind::count) {
        const auto n = static_cast<std::uint32_t>(v);
        std::memcpy(bytes, &n, 4);
      } else {
        bytes[0] = static_cast<char>(static_cast<std::int8_t>(v));
      }
      out.append(bytes, npy_size(c.kind));
    }
  }
  return out;
}

}  // namespace

const std::vector<std::string>& study_table_formats() {
  static const std::vector<std::string> formats{"csv", "json", "npy"};
  return formats;
}

std::string print_study_table(const std::vector<StudyColumn>& columns, const std::string& format, int precision) {
  if (format == "csv") return csv_table(columns, precision);
  if (format == "json") return json_table(columns, precision);
  if (format == "npy") return npy_table(columns);
  throw InputError("a design study is written as csv, json or npy, not \"" + format + "\"");
}

}  // namespace kinema
