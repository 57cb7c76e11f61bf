// A design study's table (engine/analysis/design_study's study_columns) for data tools:
// CSV (a design a row, each column named with its unit), JSON (the units, then a design an
// object) or a NumPy structured array (.npy, a field a column). Formats only.
#pragma once

#include <string>
#include <vector>

#include "engine/analysis/design_study.hpp"

namespace kinema {

/// The formats print_study_table writes.
const std::vector<std::string>& study_table_formats();

/// The table in `format` (csv, json or npy); precision: significant digits in CSV and JSON
/// (0: 12 in CSV, round-trip in JSON). NaN is an empty CSV cell, null in JSON; the class
/// of a four-bar is its words ("crank-rocker", "n/a") in CSV and JSON, its GrashofClass
/// code (int8) in npy.
std::string print_study_table(const std::vector<StudyColumn>& columns, const std::string& format, int precision);

}  // namespace kinema
