// A problem set's documents (kinema problems, docs/problems.md): per variant a student's
// sheet in LaTeX (the statement, the drawing to scale, the given data in the file's units,
// what to find; no answer), the key's answers section (the worked solution of kinema latex
// prints it, job.answers), and the class's tables: CSV, the JSON `kinema check` reads,
// Moodle XML (numerical questions with their tolerance) and a CSV of formula questions for
// Canvas or PrairieLearn. Formats only: the set, its answers and drawings are computed
// before (engine/problems, engine/run/problem_files).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "engine/analysis/analysis.hpp"
#include "engine/problems/problem_set.hpp"

namespace kinema {

/// A find name in LaTeX math ("omega3" -> \omega_{3}, "vP" -> v_{P}), without the $.
std::string problem_quantity_latex(const ConstraintSystem& system, const std::string& name);

/// The key's section of the asked answers, each boxed, in the output units: it leads the
/// key, after the data.
std::string problem_answers_latex(const ConstraintSystem& system, const std::vector<ProblemAnswer>& answers);

/// A student's sheet for `variant`: `state` and `at` the drawing's value (the first asked,
/// analysed with drawings) and `link_labels` the analysis' link numbers.
void write_problem_sheet(std::ostream& out, const ProblemSet& set, const ProblemVariant& variant,
                         const MotionState& state, const ValueAnalysis& at, const std::vector<std::string>& link_labels);

/// One row per variant: its given values, then each answer, in the file's and eval's units.
std::string problem_class_csv(const ProblemSet& set);

/// The class table `kinema check` reads: {"source", "seed", "count", "tolerance", "variants"}
/// (docs/problems.md); `source` the mechanism file relative to the JSON's directory.
std::string problem_class_json(const ProblemSet& set, const std::string& source);

/// Moodle XML: one numerical question per variant and asked answer, with its tolerance.
std::string problem_moodle_xml(const ProblemSet& set, const std::string& title);

/// Formula questions (Canvas, PrairieLearn): per variant its given values and each answer
/// with its absolute tolerance.
std::string problem_formula_csv(const ProblemSet& set);

/// Text for XML character data and attributes: & < > " ' escaped, control characters refused
/// upstream (a file's text is checked when read).
std::string xml_escape(const std::string& text);

}  // namespace kinema
