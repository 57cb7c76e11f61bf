// A class table as `kinema problems` writes it (set/class.json), read for `kinema check`:
// the mechanism file the set was drawn from, the tolerance answers are held to, and each
// variant's parameters (SI) and asked answers. Format: docs/check.md.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "readers/answers_file.hpp"

namespace kinema {

/// A parameter of a variant: its name in the mechanism file (or the driver's rate's name),
/// its SI value, and the value as written for people ("300", "mm").
struct ClassParameter {
  std::string name;
  double si = 0.0;
  std::string value, unit;
};

/// An answer the variant asks for: the quantity and the input value, as written and in SI.
struct ClassAnswer {
  std::string quantity, at;
  double at_si = 0.0;
};

struct ClassVariant {
  long number = 0;
  std::vector<ClassParameter> parameters;
  std::vector<ClassAnswer> answers;
};

struct ClassTable {
  std::string path;
  std::string source;  ///< The mechanism file, resolved against the class table's directory.
  std::optional<AnswerTolerance> tolerance;
  std::vector<ClassVariant> variants;
};

/// Reads class.json; InputError naming the file and the entry for what is missing or wrong.
ClassTable read_class_table(const std::string& path);
/// The same from text in memory (`path` resolves the source and names the file).
ClassTable read_class_table_text(const std::string& text, const std::string& path);

/// The variant numbered `number`; InputError listing the table's numbers when there is none.
const ClassVariant& class_variant(const ClassTable& table, long number);

}  // namespace kinema
