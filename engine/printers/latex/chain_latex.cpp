#include "engine/printers/latex/chain_latex.hpp"

#include <algorithm>

#include "engine/analysis/output_scale.hpp"
#include "engine/base/number_format.hpp"

namespace kinema {
namespace {

using GiNaC::ex;

// A frame or point name as a subscript: text, escaped (names are identifiers, but _ is special).
std::string named(const std::string& name) { return "\\text{" + latex_escape_text(name) + "}"; }


bool is_zero(const ChainVector& v) {
  for (const ex& c : v.formula)
    if (!c.is_zero()) return false;
  return true;
}

// name = [column] = (numbers) unit, or for a long vector the numbers first, then each
// component's formula broken over lines; a zero vector as 0.
void vector_rows(std::vector<LatexRow>& rows, const TextbookForm& form, const std::string& name, const ChainVector& v,
                 const std::string& unit, const std::string& basis, bool boxed, const std::string& comment, double budget) {
  if (is_zero(v)) {
    rows.push_back({name + " &= \\mathbf{0}", comment});
    return;
  }
  std::string numbers = "(";
  // Each component shown with the others: round-off beside them is 0.
  const double with = largest_magnitude(v.value.data(), 3);
  for (std::size_t c = 0; c < 3; ++c) numbers += (c ? ",\\ " : "") + latex_number(zero_at_scale(v.value[c], with));
  numbers += ")\\,\\mathrm{" + unit + "}";
  if (boxed) numbers = "\\boxed{" + numbers + "}";
  double longest = 0;
  for (const ex& c : v.formula) longest = std::max(longest, latex_width(form(c, TextbookForm::Style::latex)));
  if (latex_width(name) + longest + latex_width(numbers) < budget - 12) {
    rows.push_back({name + " &= " + latex_column(v.formula, form) + " = " + numbers, comment});
    return;
  }
  rows.push_back({name + " &= " + numbers, comment});
  static const char* const axes[3] = {"x", "y", "z"};
  for (std::size_t c = 0; c < 3; ++c) {
    const std::vector<std::string> lines = form.latex_lines(v.formula[c], 0, nullptr, budget - 22);
    for (std::size_t k = 0; k < lines.size(); ++k) {
      rows.push_back({k == 0 ? "&\\quad \\text{along } \\hat{\\mathbf{" + std::string(axes[c]) + "}}_{" + basis + "}:\\ " + lines[k]
                             : "&\\qquad " + lines[k],
                      ""});
    }
  }
}

std::string vector_comment(const std::string& name, const ChainVector& v, const TextbookForm& form) {
  const auto text = [&](const ex& e) { return form(e, TextbookForm::Style::text); };
  return "kinema vector: " + name + " = [" + text(v.formula[0]) + ", " + text(v.formula[1]) + ", " + text(v.formula[2]) + "]";
}

}  // namespace

std::string chain_instant_latex(const ConstraintSystem& system, const ChainAtInstant& chain) {
  const OutputScale scale(system);
  const DocumentNumbers number(system);  // round-off as 0
  std::string text = system.input.dimension == Dimension::time ? "At the instant $t = 0$ (" : "At the instant (";
  for (std::size_t i = 0; i < chain.values.size(); ++i) {
    const auto& [q, value] = chain.values[i];
    text += (i ? ", $" : "$") + to_latex(q.symbol) + " = " + number(scale.coordinate(q.dimension, value), q.dimension, 0) +
            (q.dimension == Dimension::angle ? "^{\\circ}" : "\\,\\mathrm{" + latex_escape_text(scale.length_unit) + "}") +
            "$";
  }
  return text + "), vectors along the axes of " + latex_escape_text(chain.basis) +
         (chain.basis == chain.observer ? " (the observer)" : "") + ", in SI units";
}

namespace {
// The chain's floats carry the digits they need (chain_at_instant): printed as they are.
TextbookForm exact_floats(const TextbookForm& form) {
  TextbookForm exact = form;
  exact.set_exact_floats(true);
  return exact;
}
}  // namespace

std::vector<LatexRow> chain_frame_rows(const ChainAtInstant& chain, const TextbookForm& textbook, double budget) {
  const TextbookForm form = exact_floats(textbook);
  std::vector<LatexRow> rows;
  const std::string& o = chain.observer;
  for (const ChainFrameAtInstant& f : chain.frames) {
    std::string sum;
    for (const AngularVelocityTerm& t : f.terms) {
      const bool minus = is_negative_term(t.rate);
      sum += (sum.empty() ? (minus ? "-" : "") : (minus ? " - " : " + ")) + form(minus ? -t.rate : t.rate, TextbookForm::Style::latex) +
             "\\,\\hat{\\mathbf{" + t.axis + "}}_{" + named(t.frame) + "}";
    }
    const std::string w = "\\boldsymbol{\\omega}_{" + named(f.name + "/" + o) + "}";
    rows.push_back({w + " &= " + (sum.empty() ? "\\mathbf{0}" : sum), "frame " + f.name});
    vector_rows(rows, form, "", f.angular_velocity, "rad/s", named(chain.basis), false,
                vector_comment("w_" + f.name, f.angular_velocity, form), budget);
    // alpha term by term: each rate's change along its axis, and the axis carried round
    // by the frame it belongs to.
    std::vector<std::string> parts;
    for (const AngularVelocityTerm& t : f.terms) {
      const std::string axis = "\\hat{\\mathbf{" + t.axis + "}}_{" + named(t.frame) + "}";
      const std::string rate = form(t.rate, TextbookForm::Style::latex);
      parts.push_back("\\tfrac{d}{dt}(" + rate + ")\\," + axis);
      if (t.frame != o) parts.push_back("\\boldsymbol{\\omega}_{" + named(t.frame + "/" + o) + "}\\times(" + rate + "\\," + axis + ")");
    }
    // The parts over as many lines as they need.
    std::vector<std::string> lines = {""};
    for (const std::string& part : parts) {
      if (!lines.back().empty() && latex_width(lines.back() + " + " + part) > budget - 12) lines.push_back("");
      lines.back() += (lines.back().empty() ? (lines.size() == 1 ? "" : "+ ") : " + ") + part;
    }
    rows.push_back({"\\boldsymbol{\\alpha}_{" + named(f.name + "/" + o) + "} = \\frac{d}{dt}" + w + " &= " +
                        (parts.empty() ? "\\mathbf{0}" : lines.front()),
                    ""});
    for (std::size_t k = 1; k < lines.size(); ++k) rows.push_back({"&\\quad " + lines[k], ""});
    vector_rows(rows, form, "", f.angular_acceleration, "rad/s^2", named(chain.basis), false,
                vector_comment("alpha_" + f.name, f.angular_acceleration, form), budget);
  }
  return latex_fit_rows(rows, budget);
}

std::vector<LatexRow> chain_point_rows(const ChainAtInstant& chain, const TextbookForm& textbook, double budget) {
  const TextbookForm form = exact_floats(textbook);
  std::vector<LatexRow> rows;
  for (const ChainPointAtInstant& p : chain.points) {
    const std::string F = named(p.frame), P = named(p.name);
    for (const auto* part : {&p.velocity, &p.acceleration}) {
      for (const ChainVector& v : *part) {
        std::string name, unit = part == &p.velocity ? "m/s" : "m/s^2", comment;
        bool result = false;
        switch (v.term) {
          case ChainTerm::position: name = "\\mathbf{r}_{" + named(p.name + "/" + p.frame) + "}"; unit = "m"; break;
          case ChainTerm::frame_velocity: name = "\\mathbf{v}_{" + F + "}"; break;
          case ChainTerm::transport: name = "\\boldsymbol{\\omega}\\times\\mathbf{r}"; break;
          case ChainTerm::relative_velocity: name = "\\mathbf{v}^{\\mathrm{rel}}"; break;
          case ChainTerm::velocity:
            name = "\\mathbf{v}_{" + P + "} = \\mathbf{v}_{" + F + "} + \\boldsymbol{\\omega}\\times\\mathbf{r} + "
                   "\\mathbf{v}^{\\mathrm{rel}}";
            result = true;
            comment = vector_comment("v_" + p.name, v, form);
            break;
          case ChainTerm::frame_acceleration: name = "\\mathbf{a}_{" + F + "}"; break;
          case ChainTerm::tangential: name = "\\boldsymbol{\\alpha}\\times\\mathbf{r}"; break;
          case ChainTerm::centripetal:
            name = "\\boldsymbol{\\omega}\\times(\\boldsymbol{\\omega}\\times\\mathbf{r})";
            break;
          case ChainTerm::coriolis: name = "2\\boldsymbol{\\omega}\\times\\mathbf{v}^{\\mathrm{rel}}"; break;
          case ChainTerm::relative_acceleration: name = "\\mathbf{a}^{\\mathrm{rel}}"; break;
          case ChainTerm::acceleration:
            name = "\\mathbf{a}_{" + P + "}";
            result = true;
            comment = vector_comment("a_" + p.name, v, form);
            break;
          default: break;
        }
        if (v.term == ChainTerm::position) comment = "point " + p.name + " in " + p.frame;
        vector_rows(rows, form, name, v, unit, named(chain.basis), result, comment, budget);
      }
    }
  }
  return latex_fit_rows(rows, budget);
}

}  // namespace kinema
