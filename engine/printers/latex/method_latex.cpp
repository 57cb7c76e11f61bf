#include "engine/printers/latex/method_latex.hpp"

#include "engine/printers/latex/latex_format.hpp"

namespace kinema {

std::vector<LatexRow> method_rows(const MethodStep& step, bool acceleration, const TextbookForm& form, double budget) {
  const auto latex = [&](const GiNaC::ex& e) { return form(e, TextbookForm::Style::latex); };
  std::vector<LatexRow> rows;
  // The heading and a note as text that wraps (in the first column, a long heading
  // pushed every formula to the right).
  rows.push_back(latex_intertext(latex_escape_text(step.heading)));
  if (!step.note.empty()) rows.push_back(latex_intertext(latex_escape_text("(" + step.note + ")")));
  for (const MethodRelation& r : acceleration ? step.acceleration : step.velocity) {
    switch (r.kind) {
      case MethodRelation::Kind::statement:
        rows.push_back({"& " + r.latex, ""});
        break;
      case MethodRelation::Kind::component:
        if (r.text == "position") break;  // the statement says it
        rows.push_back({"& " + r.latex + ":\\quad " + latex(r.left) + " = " + latex(r.right), ""});
        break;
      case MethodRelation::Kind::solution:
        // Long solutions broken over lines inside the text width.
        for (const LatexRow& row : latex_broken_rows(latex(r.left), form.latex_lines(r.right, 0, nullptr, budget),
                                                     "", "kinema: " + form(r.left, TextbookForm::Style::text) + " = " +
                                                         form(r.right, TextbookForm::Style::text)))
          rows.push_back(row);
        break;
    }
  }
  return latex_fit_rows(rows, budget);
}

std::string method_title(DerivationMethod method) {
  switch (method) {
    case DerivationMethod::loops: return "vector loops";
    case DerivationMethod::relative_velocity: return "relative velocities";
    case DerivationMethod::joint_coordinates: return "joint coordinates";
  }
  return "";
}

}  // namespace kinema
