// What `kinema check` found, for its printers (engine/printers/check_report.hpp): each
// answer as given and as expected, right or wrong, and for a wrong one the mistakes of
// the catalogue (engine/problems/mistake_catalogue.hpp) that reproduce it. Data only.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "engine/base/source_location.hpp"
#include "readers/answers_file.hpp"

namespace kinema {

/// A mistake of the catalogue that gives the answer: its name ("sign_reversed"), in words,
/// the way it was made ("omega4", "b a thousand times too large"; may be empty) and the
/// value it gives (the answer's unit).
struct MistakeMatch {
  std::string name, words, detail;
  double value = 0.0;
};

struct AnswerVerdict {
  SourceLocation where;
  std::string quantity;  ///< As written ("vP").
  std::string column;    ///< The result column it names ("P_speed").
  std::string unit;      ///< The column's output unit: given and expected values are in it.
  std::string at;        ///< The input value, as written (or the key's when not written).
  double at_si = 0.0;
  std::string given;         ///< The value as written.
  double given_value = 0.0;  ///< In `unit`.
  bool unit_assumed = false;  ///< Written without a unit: taken as `unit`.
  double expected = 0.0;
  /// A design figure (engine/problems/design_answers): no input value (at empty); one
  /// that is a class in words (grashof) is graded as text against expected_text.
  bool figure = false;
  std::string expected_text;
  bool right = false;
  /// Wrong answers only: the catalogue's mistakes that reproduce it, in catalogue order
  /// (the first is the likely one); empty when none does.
  std::vector<MistakeMatch> mistakes;
};

struct CheckReport {
  std::string answers_file;  ///< As given.
  std::string source;        ///< The mechanism file the answers are checked against.
  std::optional<long> variant;
  AnswerTolerance tolerance;
  std::vector<AnswerVerdict> verdicts;  ///< In the order of the answers file.

  std::size_t wrong_count() const {
    std::size_t wrong = 0;
    for (const AnswerVerdict& v : verdicts) wrong += v.right ? 0 : 1;
    return wrong;
  }
};

}  // namespace kinema
