// The mistakes students make in velocity and acceleration analysis, each a named entry
// that evaluates the mechanism the mistaken way: sign or sense reversed, degrees for
// radians and radians for degrees, the driver's rpm taken as rad/s, the other assembly,
// the Coriolis term omitted or doubled, a relative velocity given for an absolute one,
// another link's rate, a length in mm taken as m (or m as mm). `kinema check` names the
// mistake of a wrong answer by finding the entry whose value reproduces it.
#pragma once

#include <string>
#include <vector>

#include "engine/model.hpp"

namespace kinema {

/// One position's result columns (result_columns' order, output units: kinema eval's
/// numbers); NaN where a column has no value.
using ResultRow = std::vector<double>;

/// Where a mechanism is evaluated: its model, the input value and the driver's rates (SI),
/// and the rate as written ("60 rpm": what a student reads).
struct EvaluationPoint {
  const Model* model = nullptr;
  double at = 0.0, rate = 0.0, second_rate = 0.0;
  std::string rate_text;
};

/// A solved position with its columns.
struct SolvedRow {
  MotionState state;
  ResultRow values;
};

/// The mechanism solved at the point (on the file's assembly, as kinema eval solves it);
/// AssemblyError or SingularPositionError (describe_failure's words) where it has no rates.
SolvedRow solve_row(const EvaluationPoint& point);

/// The columns of a state (status ok) of the model's system.
ResultRow row_of(const Model& model, const MotionState& state);

/// One way of making a mistake and the row of values it gives (NaN for a column the
/// mistake says nothing about).
struct MistakenRow {
  std::string detail;  ///< Which way, when there are several ("omega4"); may be empty.
  ResultRow values;
};

struct Mistake {
  const char* name;   ///< For graders: "sign_reversed".
  const char* words;  ///< For people: "sign or sense reversed".
  /// The rows the mistake gives at the point, from the correct solution; none where the
  /// mistake cannot be made (no rpm written, no Coriolis term, no other assembly).
  std::vector<MistakenRow> (*rows)(const EvaluationPoint& point, const SolvedRow& correct);
};

/// Every mistake, most likely first (the first that reproduces an answer is named).
const std::vector<Mistake>& mistake_catalogue();

}  // namespace kinema
