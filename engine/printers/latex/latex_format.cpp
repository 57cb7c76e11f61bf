#include "engine/printers/latex/latex_format.hpp"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <sstream>

#include "engine/printers/latex/latex_unicode.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/base/user_text.hpp"
#include "engine/constraints/expression_parts.hpp"
#include "engine/base/units.hpp"

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

DocumentNumbers::DocumentNumbers(const ConstraintSystem& system) : problem_(system) {}

double DocumentNumbers::cleaned(double shown, Dimension dimension, int order, double shown_with) const {
  return zero_at_scale(shown, std::max(problem_.of(dimension, order), shown_with));
}

std::string DocumentNumbers::operator()(double shown, Dimension dimension, int order, int digits, double shown_with) const {
  return latex_number(cleaned(shown, dimension, order, shown_with), digits);
}

std::string latex_figure_caption(const std::string& text) {
  // \nopagebreak: the caption stays on its drawing's page; \interlinepenalty: a caption of
  // several lines (a drawing's scales) is never broken across pages.
  return "\\par\\nopagebreak\\smallskip\\refstepcounter{figure}{\\small Figure~\\thefigure: " + text +
         "\\interlinepenalty=10000\\par}\n";
}

std::string DocumentNumbers::read_off(double shown, Dimension dimension, int order) const {
  return latex_number(cleaned(std::stod(format_significant(shown, 4)), dimension, order), 7);
}

std::string DocumentNumbers::ratio(double value, int digits) const {
  return latex_number(zero_at_scale(value, 1), digits);
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

LatexRow latex_intertext(const std::string& escaped_text, const std::string& comment) {
  return {"\\intertext{" + escaped_text + "}", comment};
}

bool is_intertext(const std::string& row) { return row.rfind("\\intertext{", 0) == 0; }

namespace {

// The first & of a row outside braces and environments (npos: none), and the places a
// row may break: before " + ", " - " and " = " where a break compiles (not in braces,
// an environment such as bmatrix, or \left...\right), each with how deep in
// parentheses it is (a break inside sin(theta2 + theta4) is the last resort).
struct RowShape {
  std::size_t tab = std::string::npos;
  std::vector<std::pair<std::size_t, int>> breaks;
};

// Nothing but spaces and \quad: a sign after it is the row's first (no break there).
bool only_spacing(std::string text) {
  for (const char* space : {"\\qquad", "\\quad"})
    for (auto at = text.find(space); at != std::string::npos; at = text.find(space)) text.erase(at, std::string(space).size());
  return text.find_first_not_of(' ') == std::string::npos;
}

RowShape row_shape(const std::string& text) {
  RowShape shape;
  int depth = 0, parentheses = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (ch == '\\') {
      std::size_t end = 0;
      const std::string name = latex_command_name(text, i, end);
      if (name == "begin" || name == "left") ++depth;
      else if (name == "end" || name == "right") --depth;
      i = end > i + 1 ? end - 1 : i + 1;  // \{, \, and the like: two characters
      continue;
    }
    if (ch == '{') {
      ++depth;
    } else if (ch == '}') {
      --depth;
    } else if (ch == '(') {
      ++parentheses;
    } else if (ch == ')') {
      --parentheses;
    } else if (depth == 0 && ch == '&' && shape.tab == std::string::npos) {
      shape.tab = i;
    } else if (depth == 0 && ch == ' ' && shape.tab != std::string::npos && i > shape.tab + 1 && i + 2 < text.size() &&
               (text[i + 1] == '+' || text[i + 1] == '-' || text[i + 1] == '=') && text[i + 2] == ' ' &&
               !only_spacing(text.substr(shape.tab + 1, i - shape.tab - 1))) {
      shape.breaks.push_back({i, parentheses});
    }
  }
  return shape;
}

// The parts of text[from, to) split at the breaks of the least depth in it; a part too
// wide for `room` split again at its deeper breaks.
void split_parts(const std::string& text, std::size_t from, std::size_t to, const std::vector<std::pair<std::size_t, int>>& breaks,
                 double room, std::vector<std::string>& parts) {
  int least = INT_MAX;
  for (const auto& [at, level] : breaks)
    if (at > from && at < to) least = std::min(least, level);
  if (least == INT_MAX || latex_width(text.substr(from, to - from)) <= room) {
    parts.push_back(text.substr(from, to - from));
    return;
  }
  std::size_t start = from;
  for (const auto& [at, level] : breaks) {
    if (at <= from || at >= to || level != least) continue;
    split_parts(text, start, at, breaks, room, parts);
    start = at + 1;  // the next part starts at its sign
  }
  split_parts(text, start, to, breaks, room, parts);
}

}  // namespace

std::vector<LatexRow> latex_fit_rows(const std::vector<LatexRow>& rows, double budget) {
  std::vector<LatexRow> fitted;
  for (const LatexRow& row : rows) {
    const RowShape shape = row_shape(row.text);
    // A little room over the budget: rows made to it start with \quad.
    if (is_intertext(row.text) || shape.tab == std::string::npos || latex_width(row.text.substr(shape.tab)) <= budget + 3 ||
        shape.breaks.empty()) {
      fitted.push_back(row);
      continue;
    }
    // Greedy: as many parts on a row as fit (continuation rows are indented by \qquad).
    std::vector<std::string> parts;
    split_parts(row.text, shape.tab + 1, row.text.size(), shape.breaks, budget - 4, parts);
    std::string line = parts.front();
    bool first = true;
    const auto flush = [&] {
      fitted.push_back({first ? row.text.substr(0, shape.tab + 1) + line : "&\\qquad " + line, first ? row.comment : ""});
      first = false;
    };
    for (std::size_t k = 1; k < parts.size(); ++k) {
      const double room = first ? budget : budget - 4;
      if (latex_width(line + " " + parts[k]) > room && latex_width(line) > 0) {
        flush();
        line = parts[k];
      } else {
        line += " " + parts[k];
      }
    }
    flush();
  }
  return fitted;
}

namespace {

// Characters of one line of the .tex file: pdflatex reads a line into a buffer of 200,000
// and stops past it ("Unable to read an entire line"); the derivatives of cos nested 32
// deep, with their formula in GiNaC syntax as a comment, made lines of 600,000.
constexpr std::size_t kTexLineChars = 4000;

// The row's text with a line break for a space where a line would be longer (a line
// break is a space to TeX, and a space in a formula ends no command).
std::string wrapped_row(const std::string& text) {
  std::string out = text;
  std::size_t line_start = 0;
  while (out.size() - line_start > kTexLineChars) {
    const std::size_t space = out.rfind(' ', line_start + kTexLineChars);
    if (space == std::string::npos || space <= line_start) break;  // no space: left as it is
    out[space] = '\n';
    line_start = space + 1;
  }
  return out;
}

// A comment over as many lines as it needs, each one a comment.
std::string wrapped_comment(const std::string& comment) {
  std::string out = " % " + comment.substr(0, kTexLineChars);
  for (std::size_t at = kTexLineChars; at < comment.size(); at += kTexLineChars)
    out += "\n  % " + comment.substr(at, kTexLineChars);
  return out;
}

}  // namespace

std::string latex_align_rows(const std::vector<LatexRow>& rows) {
  std::string out;
  std::size_t in_block = 0;  // rows since the align* (or the last split) began
  for (std::size_t r = 0; r < rows.size(); ++r) {
    // pdflatex's time grows with the square of an align*'s rows (the derivations of nests
    // 32 deep, blocks of 3,000 to 4,000 rows, took 20 s; in blocks of 200, 2.6 s). So past
    // kAlignBlockRows the align* is closed and another opened (not next to an \intertext,
    // which needs a row before it). A formula that long goes on in the next block, its
    // continuation rows aligned among themselves.
    const bool split = r + 1 < rows.size() && in_block + 1 >= kAlignBlockRows && !is_intertext(rows[r].text) &&
                       !is_intertext(rows[r + 1].text);
    out += "  " + wrapped_row(rows[r].text) + (r + 1 < rows.size() && !is_intertext(rows[r].text) && !split ? " \\\\" : "");
    if (!rows[r].comment.empty()) out += wrapped_comment(rows[r].comment);
    out += "\n";
    ++in_block;
    if (split) {
      out += "\\end{align*}\n\\begin{align*}\n";
      in_block = 0;
    }
  }
  return out;
}

}  // namespace kinema
