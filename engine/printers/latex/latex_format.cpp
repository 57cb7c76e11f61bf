#include <kinema/engine/printers/latex/latex_format.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <kinema/engine/printers/latex/latex_unicode.hpp>
#include <kinema/engine/report/number_format.hpp>
#include <kinema/engine/report/output_scale.hpp>
#include <kinema/engine/report/user_text.hpp>
#include <kinema/engine/symbolic/expression_parts.hpp>

namespace kinema {

std::string latex_escape_text(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    switch (c) {
      case '\\': out += "\\textbackslash{}"; break;
      case '{': out += "\\{"; break;
      case '}': out += "\\}"; break;
      case '$': out += "\\$"; break;
      case '&': out += "\\&"; break;
      case '#': out += "\\#"; break;
      case '%': out += "\\%"; break;
      case '_': out += "\\_"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '<': out += "\\textless{}"; break;
      case '>': out += "\\textgreater{}"; break;
      case '|': out += "\\textbar{}"; break;
      default: {
        const unsigned long code = next_code_point(text, i);
        // Control characters (a line break, ESC, DEL, NUL, ...) stop pdflatex: a space instead.
        if (is_control_character(code)) out += ' ';
        else if (code < 0x80) out += c;
        else out += latex_for_code_point(code);
      }
    }
  }
  return out;
}

std::string latex_number(double value, int digits) {
  std::string text = format_significant(value, digits);
  const auto e = text.find('e');
  if (e != std::string::npos) {  // 1e-05 -> 1\cdot10^{-5}
    const int exponent = std::stoi(text.substr(e + 1));
    text = text.substr(0, e) + "\\cdot 10^{" + std::to_string(exponent) + "}";
  }
  return text;
}

DocumentNumbers::DocumentNumbers(const ConstraintSystem& system) {
  const OutputScale scale(system);
  double size = 0;
  for (const SystemParameter& p : system.parameters)
    if (p.dimension == Dimension::length && std::isfinite(p.value)) size = std::max(size, std::fabs(p.value));
  if (size == 0) size = 1;  // no length given: the metre
  length_ = size / scale.length;
  // A length driver's rate over the size is its angular rate.
  const Driver& input = system.input;
  const double per = input.dimension == Dimension::length ? 1 / size : 1;
  rate_ = std::fabs(input.rate_value) * per;
  second_rate_ = rate_ * rate_ + std::fabs(input.second_rate_value) * per;
  if (!(rate_ > 0) || !std::isfinite(rate_)) rate_ = 1;
  if (!(second_rate_ > 0) || !std::isfinite(second_rate_)) second_rate_ = 1;
}

double DocumentNumbers::zero_below(Dimension dimension, int order) const {
  constexpr double accuracy = 1e-12;  // the solvers' relative accuracy, with room
  const double time = order == 0 ? 1 : order == 1 ? rate_ : second_rate_;
  switch (dimension) {
    case Dimension::length: return accuracy * length_ * time;
    case Dimension::angle: return accuracy * time * (order == 0 ? 180 / M_PI : 1);  // values in deg, rates in rad/s
    default: return 0;
  }
}

double DocumentNumbers::cleaned(double shown, Dimension dimension, int order) const {
  return std::fabs(shown) < zero_below(dimension, order) ? 0.0 : shown;
}

std::string DocumentNumbers::operator()(double shown, Dimension dimension, int order, int digits) const {
  return latex_number(cleaned(shown, dimension, order), digits);
}

std::string to_latex(const GiNaC::ex& e) { return TextbookForm()(e, TextbookForm::Style::latex); }

std::string latex_exp(const GiNaC::ex& angle) {
  const std::string a = to_latex(angle);
  return "e^{i" + (GiNaC::is_a<GiNaC::add>(angle) ? "(" + a + ")" : a) + "}";
}

namespace {

template <class Entry>
std::string column_text(const std::vector<GiNaC::ex>& entries, Entry entry) {
  std::string text = "\\begin{bmatrix}";
  for (std::size_t i = 0; i < entries.size(); ++i) text += (i ? " \\\\ " : " ") + entry(entries[i]);
  return text + " \\end{bmatrix}";
}

template <class Entry>
std::string matrix_text(const GiNaC::matrix& matrix, Entry entry) {
  std::string text = "\\begin{bmatrix}";
  for (unsigned i = 0; i < matrix.rows(); ++i) {
    for (unsigned j = 0; j < matrix.cols(); ++j) text += (j ? " & " : " ") + entry(matrix(i, j));
    text += i + 1 < matrix.rows() ? " \\\\" : " ";
  }
  return text + "\\end{bmatrix}";
}

}  // namespace

std::string latex_column(const std::vector<GiNaC::ex>& entries) {
  return column_text(entries, [](const GiNaC::ex& e) { return to_latex(e); });
}

std::string latex_column(const std::vector<GiNaC::ex>& entries, const TextbookForm& form) {
  return column_text(entries, [&](const GiNaC::ex& e) { return form(e, TextbookForm::Style::latex); });
}

std::string latex_matrix(const GiNaC::matrix& matrix, const TextbookForm& form) {
  return matrix_text(matrix, [&](const GiNaC::ex& e) { return form(e, TextbookForm::Style::latex); });
}

std::string latex_vector_loop(const EquationGroup& loop) {
  using GiNaC::ex;
  // Terms c*exp(I*angle) print as c\,e^{i angle}, as course notes write link vectors.
  auto term_text = [&](const ex& term) {
    const LinkVector link = split_link_vector(term);
    if (!link.polar) return to_latex(term);
    ex coefficient = link.length;
    // -(CD + CE) rather than (-CE - CD): take a common minus sign out of a sum.
    bool negated = false;
    if (GiNaC::is_a<GiNaC::add>(coefficient)) {
      negated = true;
      for (const ex& t : coefficient) {
        const ex factor = GiNaC::is_a<GiNaC::mul>(t) ? t.op(t.nops() - 1) : ex(1);
        negated = negated && GiNaC::is_a<GiNaC::numeric>(factor) && GiNaC::ex_to<GiNaC::numeric>(factor).is_negative();
      }
      if (negated) coefficient = (-coefficient).expand();
    }
    std::string c = to_latex(coefficient);
    if (c == "1") c.clear();
    if (c == "-1") c = "-";
    if (GiNaC::is_a<GiNaC::add>(coefficient)) c = "\\left(" + c + "\\right)";
    if (negated) c = "-" + c;
    return c + "\\," + latex_exp(link.angle);
  };
  std::string text;
  for (const ex& term : loop.terms) {
    const std::string t = term_text(term);
    const bool minus = !t.empty() && t[0] == '-';
    if (text.empty()) text = t;
    else text += (minus ? " - " : " + ") + t.substr(minus ? 1 : 0);
  }
  return text;
}

std::vector<LatexRow> latex_broken_rows(const std::string& lhs, const std::vector<std::string>& lines,
                                        const std::string& suffix, const std::string& comment) {
  std::vector<LatexRow> rows;
  for (std::size_t k = 0; k < lines.size(); ++k)
    rows.push_back({k == 0 ? lhs + " &= " + lines[k] : "&\\quad " + lines[k], k == 0 ? comment : ""});
  if (suffix.empty()) return rows;
  if (lines.size() > 1 && latex_width(lines.back() + suffix) > kLatexLineBudget) rows.push_back({"&" + suffix, ""});
  else rows.back().text += suffix;
  return rows;
}

}  // namespace kinema
