// A student's answers as written, for `kinema check` (docs/check.md): a TOML file of
// [[answer]] tables or a CSV file of rows quantity,at,value[,unit], and how near an answer
// must be to count (a relative tolerance or significant figures). Only what was written is
// read here, each entry with its file:line; which quantity a name means and what a value
// is in the mechanism's units are the checker's (engine/problems/answer_check.hpp).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "engine/base/source_location.hpp"

namespace kinema {

/// How near an answer must be to the expected value to count as right.
struct AnswerTolerance {
  enum class Kind { relative, significant_figures };
  Kind kind = Kind::relative;
  double relative = 0.01;  ///< |given - expected| <= relative * |expected|.
  int figures = 3;         ///< |given - expected| <= half a unit in the last of this many figures of expected.
  /// "1 %" or "3 significant figures".
  std::string describe() const;
  /// Whether `given` counts as `reference` (both in one unit).
  bool accepts(double given, double reference) const;
};

/// "1%", "0.5 %" or a bare fraction "0.01" (0 < relative < 1); InputError naming `context` otherwise.
AnswerTolerance relative_tolerance(const std::string& text, const std::string& context);
/// 1 to 15 significant figures; InputError naming `context` otherwise.
AnswerTolerance significant_figures(long figures, const std::string& context);

/// One answer as written: the quantity's name ("omega3", "vP"), the input value it is at
/// ("30 deg"; empty when not written) and the value with its unit when one is written
/// ("-2.35 rad/s", "-2.35").
struct WrittenAnswer {
  std::string quantity, at, value;
  SourceLocation where;
};

struct AnswersFile {
  std::string path;
  std::optional<long> variant;  ///< TOML `variant = N` (a class table's variant).
  SourceLocation variant_where;
  std::vector<WrittenAnswer> answers;
};

/// Most answers in one file (a problem asks for a handful).
constexpr std::size_t kMaxAnswers = 1000;

/// Reads an answers file: CSV when its name ends in .csv, else TOML. InputError with
/// file:line for a syntax error, an unknown key, a missing quantity or value, no answers.
AnswersFile read_answers_file(const std::string& path);
/// The same from text in memory; `name` stands for the file (its extension picks the form).
AnswersFile read_answers_text(const std::string& text, const std::string& name);

}  // namespace kinema
