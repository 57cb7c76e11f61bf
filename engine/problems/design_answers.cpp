#include "engine/problems/design_answers.hpp"

#include <cmath>
#include <limits>

#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/units.hpp"

namespace kinema {

bool is_design_figure_name(const std::string& name) {
  return name == "grashof" || name == "min_transmission_angle" || name == "max_transmission_angle" ||
         name == "stroke" || name == "time_ratio" || name.rfind("stroke_", 0) == 0 || name.rfind("time_ratio_", 0) == 0;
}

std::vector<DesignAnswer> design_answers(const Model& model) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<DesignAnswer> answers;
  if (const std::optional<FourBarFigures> f = four_bar_figures(model)) {
    answers.push_back({"grashof", nan, nan, "", f->grashof});
    answers.push_back({"min_transmission_angle", from_degrees(f->least_transmission), f->least_transmission, "deg", ""});
    answers.push_back({"max_transmission_angle", from_degrees(f->greatest_transmission), f->greatest_transmission, "deg", ""});
  }
  if (model.system.input.dimension != Dimension::angle) return answers;
  const OutputScale scale(model.system);
  const std::vector<Strokes> strokes = slider_strokes(model);
  for (std::size_t k = 0; k < strokes.size(); ++k) {
    const Strokes& s = strokes[k];
    // A stroke and a time ratio are a slider's with two limit positions over a whole turn;
    // the first slider's are `stroke` and `time_ratio`, missing (as the variant's) where it
    // has other than two.
    if (!s.two_limits()) continue;
    // limit_values are in output units: a length's in the file's length unit.
    const double stroke = std::fabs(s.limit_values[1] - s.limit_values[0]);
    const DesignAnswer length{"stroke", stroke * scale.length, stroke, scale.length_unit, ""};
    const DesignAnswer ratio{"time_ratio", s.time_ratio, s.time_ratio, "", ""};
    if (k == 0) {
      answers.push_back(length);
      answers.push_back(ratio);
    }
    answers.push_back({"stroke_" + s.name, length.si, length.value, length.unit, ""});
    answers.push_back({"time_ratio_" + s.name, ratio.si, ratio.value, "", ""});
  }
  return answers;
}

std::string missing_figure_reason(const std::string& name) {
  const bool slider = name.rfind("stroke", 0) == 0 || name.rfind("time_ratio", 0) == 0;
  return "no " + name + (slider ? " (not two limit positions over a whole turn)" : "");
}

std::optional<DesignAnswer> design_answer(const std::vector<DesignAnswer>& answers, const std::string& name) {
  for (const DesignAnswer& a : answers)
    if (a.name == name) return a;
  return std::nullopt;
}

}  // namespace kinema
