#include "engine/run/problem_files.hpp"

#include <sstream>

#include "engine/analysis/analysis.hpp"
#include "engine/analysis/plot_range.hpp"
#include "engine/base/errors.hpp"
#include "engine/printers/printer.hpp"
#include "engine/printers/problems/problem_documents.hpp"
#include "engine/run/view.hpp"

namespace kinema {

std::string variant_stem(const ProblemSet& set, const ProblemVariant& variant) {
  std::string number = std::to_string(variant.number);
  const std::size_t width = std::max<std::size_t>(2, std::to_string(set.count).size());
  if (number.size() < width) number.insert(0, width - number.size(), '0');
  return "variant_" + number;
}

std::string problem_sheet(const ProblemSet& set, const ProblemVariant& variant) {
  // The drawing at the first asked value, analysed as kinema latex draws it.
  const MotionTable table = solve_motion(variant.model, {variant.at.front()});
  ViewNeeds needs;
  needs.drawings = true;
  const Analysis analysis = analyse_for_views(variant.model, &table, needs);
  std::ostringstream out;
  write_problem_sheet(out, set, variant, table[0], analysis.values.front(), analysis.link_labels);
  return out.str();
}

std::string problem_key(const ProblemVariant& variant) {
  const Model& model = variant.model;
  const MotionTable at_values = solve_motion(model, variant.at);
  const MotionTable sweep = solve_motion(model, plot_range(model.system, variant.at.front()));
  PrintJob job{model, &at_values, &sweep};
  job.answers = &variant.answers;
  std::ostringstream out;
  print_view(*find_printer(PrintKind::document, "latex"), out, job);
  return out.str();
}

std::vector<NamedFile> problem_set_files(const ProblemSet& set, const std::string& source_name, const std::string& title) {
  std::vector<NamedFile> files;
  for (const ProblemVariant& variant : set.variants) {
    const std::string stem = variant_stem(set, variant);
    files.emplace_back(stem + "_sheet.tex", problem_sheet(set, variant));
    files.emplace_back(stem + "_key.tex", problem_key(variant));
  }
  files.emplace_back("class.csv", problem_class_csv(set));
  files.emplace_back("class.json", problem_class_json(set, source_name));
  files.emplace_back("moodle.xml", problem_moodle_xml(set, title));
  files.emplace_back("formula_questions.csv", problem_formula_csv(set));
  return files;
}

}  // namespace kinema
