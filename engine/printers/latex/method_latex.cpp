#include <kinema/engine/printers/latex/method_latex.hpp>

#include <kinema/engine/printers/latex/latex_format.hpp>
#include <kinema/engine/symbolic/expression_parts.hpp>

namespace kinema {

std::vector<LatexRow> method_rows(const MethodStep& step, bool acceleration) {
  std::vector<LatexRow> rows;
  rows.push_back({"\\text{" + latex_escape_text(step.heading) + "}\\quad", ""});
  if (!step.note.empty()) rows.push_back({"& \\text{" + latex_escape_text("(" + step.note + ")") + "}", ""});
  for (const MethodRelation& r : acceleration ? step.acceleration : step.velocity) {
    switch (r.kind) {
      case MethodRelation::Kind::statement:
        rows.push_back({"& " + r.latex, ""});
        break;
      case MethodRelation::Kind::component:
        if (r.text == "position") break;  // the statement says it
        rows.push_back({"& " + r.latex + ":\\quad " + to_latex(r.left) + " = " + to_latex(r.right), ""});
        break;
      case MethodRelation::Kind::solution:
        rows.push_back({to_latex(r.left) + " &= " + to_latex(r.right),
                        "kinema: " + to_text(r.left) + " = " + to_text(r.right)});
        break;
    }
  }
  return rows;
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
