// A problem set from a mechanism file's [problem] table (docs/problems.md): variants of
// the mechanism drawn reproducibly from a seed (the varied parameters on their step grids),
// each the model with those parameter values (with_parameters: nothing derived again),
// checked against the table's conditions by evaluating it, and its asked answers computed
// as `kinema eval` computes them. Printers format the set (engine/printers/problems).
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "engine/model.hpp"
#include "engine/problems/problem_answer.hpp"
#include "readers/mechanism.hpp"

namespace kinema {

/// A reproducible stream of draws: std::mt19937_64 (its output exactly specified by the
/// standard) mapped to integers by rejection, so that a seed gives the same draws on every
/// machine (std::uniform_int_distribution's mapping is the library's own).
class ProblemDraws {
 public:
  explicit ProblemDraws(std::uint64_t seed) : engine_(seed) {}
  /// An integer in [0, n], every one equally likely.
  std::uint64_t below_or_equal(std::uint64_t n);

 private:
  std::mt19937_64 engine_;
};

/// A varied value of a variant: SI, and in the unit the file writes it in.
struct GivenValue {
  std::string name;
  double si = 0.0;
  double value = 0.0;
  std::string unit;
  int decimals = 0;  ///< Digits after the point that show the range's grid in `unit` (0.380 m for 5 mm steps).
};

struct ProblemVariant {
  int number = 0;  ///< From 1.
  Model model;     ///< The mechanism with this variant's parameters (and driver's rate).
  std::vector<GivenValue> given;      ///< The varied values, in [problem] vary's order.
  std::vector<double> at;             ///< The asked input values (SI).
  std::vector<std::string> at_texts;  ///< As shown: "30 deg".
  std::vector<ProblemAnswer> answers; ///< For each asked value, each find name in order.
};

/// How a set's answers are graded.
struct ProblemTolerance {
  double relative = 0.01;  ///< When sig_figs is 0.
  int sig_figs = 0;
  /// The absolute tolerance of an answer (Moodle's numerical questions take one).
  double absolute(double value) const;
};

struct ProblemSet {
  std::string statement;
  std::uint64_t seed = 0;
  std::size_t count = 0;
  ProblemTolerance tolerance;
  std::vector<ProblemVariant> variants;
  std::size_t draws = 0;  ///< Variants drawn in all (count + redrawn).
  /// Per condition that refused a draw ("grashof", "assembles", ...), how many it refused.
  std::vector<std::pair<std::string, std::size_t>> redrawn;
};

/// Most draws in a row that meet no condition before the set is refused as unsatisfiable
/// (conditions nothing meets are told in a second, not after count times as many).
constexpr std::size_t kMaxDrawsPerVariant = 200;
/// Most variants in a set (each is a LaTeX sheet and key).
constexpr std::size_t kMaxProblemVariants = 1000;

/// The set of `count` variants of `model` (read from a file with a [problem] table,
/// derived in full scope so that keys print its formulas) for `seed`. InputError (file:line)
/// for a bad [problem]: a find name that is no output column (the names listed), a varied
/// name that is no parameter, driver value or rate, a condition the mechanism has no
/// figure for; and when too many draws fail the conditions (how many failed each).
ProblemSet make_problem_set(const Model& model, const Problem& problem, std::size_t count, std::uint64_t seed);

/// The names `find` takes for this system: eval's output columns, then the short forms
/// vP (P_speed) and aP (P_acceleration) of its points (design figures are listed apart).
std::vector<std::string> find_names(const ConstraintSystem& system);

/// The conditions of `problem` that `variant` (a model) fails at the asked values (SI;
/// toggle_margin: within the margin of a toggle or of any of a slider's limit positions):
/// "assembles", a figure asked that the variant has not (missing_figure_reason: "no stroke
/// (not two limit positions over a whole turn)"), "grashof", "min_transmission_angle",
/// "toggle_margin", "min_answer" (of the answers it has). Empty when it meets them all.
std::vector<std::string> failed_conditions(const Model& variant, const Problem& problem, const std::vector<double>& at);

/// The answers of `variant` at `at` (SI; `at_texts` as shown) for the find names, as kinema
/// eval gives them at those values (one run, each value continued from the previous), for
/// each value in find's order, then the design figures asked, once, in find's order.
std::vector<ProblemAnswer> problem_answers(const Model& variant, const std::vector<ProblemFind>& find,
                                           const std::vector<double>& at, const std::vector<std::string>& at_texts);

}  // namespace kinema
