// The files of `kinema problems` (docs/problems.md), made in memory: per variant a
// student's sheet and a key (the worked solution of kinema latex for the variant, its
// asked answers boxed), and the class's tables and course-platform exports. The command
// writes them only once all are made, so that an error leaves nothing half-written.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "engine/problems/problem_set.hpp"

namespace kinema {

/// A file's name (in the set's directory) and its content.
using NamedFile = std::pair<std::string, std::string>;

/// "variant_07": a variant's file stem, numbered to the width of the set's count (two at least).
std::string variant_stem(const ProblemSet& set, const ProblemVariant& variant);

/// Every file of the set: for each variant <stem>_sheet.tex and <stem>_key.tex, then
/// class.csv, class.json (its source `source_name`, the copied mechanism file),
/// moodle.xml and formula_questions.csv; `title` names the Moodle category.
std::vector<NamedFile> problem_set_files(const ProblemSet& set, const std::string& source_name, const std::string& title);

/// A variant's student sheet and its key (LaTeX documents).
std::string problem_sheet(const ProblemSet& set, const ProblemVariant& variant);
std::string problem_key(const ProblemVariant& variant);

}  // namespace kinema
