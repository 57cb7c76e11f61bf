// LaTeX helpers shared by the LaTeX printers. Symbols carry their LaTeX names from
// the front end (GiNaC's TeX names); formulas print in textbook form, never in
// GiNaC's own order (which differs from one build to another).
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "engine/analysis/problem_scale.hpp"
#include "engine/constraints/constraint_system.hpp"
#include "engine/printers/textbook_form.hpp"

namespace kinema {

/// A row of an amsmath align*.
struct LatexRow {
  std::string text;     ///< The row (an & aligns it).
  std::string comment;  ///< After the row as a % comment (a solved formula in GiNaC syntax), or empty.
};

/// Glyphs a formula of a document's align* may take after its left side (11 pt, 2 cm margins).
constexpr double kLatexLineBudget = 68;

/// A formula broken over lines (TextbookForm::latex_lines) as align* rows:
/// "lhs &= line 1", "&\quad line 2", ..., `suffix` (" = 3.2\,rad/s") after the last or
/// on a row of its own when it does not fit; `comment` on the first row.
std::vector<LatexRow> latex_broken_rows(const std::string& lhs, const std::vector<std::string>& lines,
                                        const std::string& suffix = "", const std::string& comment = "");

/// Glyphs a whole row of `derive --format latex` may take after its & in a plain article
/// (10 pt, 345 pt text width), where that block is meant to be pasted.
constexpr double kPlainArticleBudget = 40;

/// A row of text in an align* (amsmath \intertext: it wraps as a paragraph does). It
/// comes before a row of math, never last; rows are joined by latex_align_rows.
LatexRow latex_intertext(const std::string& escaped_text, const std::string& comment = "");
bool is_intertext(const std::string& row);

/// Rows wider than `budget` glyphs after their & broken before a + , - or = outside
/// braces, environments and \left...\right, onto rows "&\qquad ..." (a part that cannot
/// be broken stays whole).
std::vector<LatexRow> latex_fit_rows(const std::vector<LatexRow>& rows, double budget);

/// Rows an align* holds before latex_align_rows closes it and opens another (more than any
/// sample's block: a long derivation only).
constexpr std::size_t kAlignBlockRows = 200;

/// The rows of an align*, each ended by \\ but the last and an \intertext, comments after;
/// every kAlignBlockRows rows "\end{align*}\begin{align*}" (the caller writes the first
/// \begin and the last \end).
std::string latex_align_rows(const std::vector<LatexRow>& rows);

/// User text (titles, descriptions) for LaTeX text mode: every special character
/// is printed as itself, so a file cannot inject commands (\input{...} prints as text).
std::string latex_escape_text(const std::string& text);

/// An expression in LaTeX (the symbols' own LaTeX names), in textbook form without a
/// system's order of symbols (TextbookForm's default).
std::string to_latex(const GiNaC::ex& e);

/// e^{i angle} (the angle parenthesised when it is a sum).
std::string latex_exp(const GiNaC::ex& angle);

/// A column vector as amsmath bmatrix.
std::string latex_column(const std::vector<GiNaC::ex>& entries);
/// A column and a matrix, each entry in the system's textbook form.
std::string latex_column(const std::vector<GiNaC::ex>& entries, const TextbookForm& form);
std::string latex_matrix(const GiNaC::matrix& matrix, const TextbookForm& form);

/// A planar loop as course notes write it, its terms in the order written:
/// a\,e^{i\theta_{2}} + b\,e^{i\theta_{3}} - ...
std::string latex_vector_loop(const EquationGroup& loop);

/// Where a worked solution starts a part on a new page: a new page only when the page so
/// far is nearly half full, so that the tail of a derivation or of a table (the
/// rest of a page that ran over) is never a page of its own (plain TeX, as a fragment
/// compiles in anyone's notes: \pagetotal is the current page's height after \par).
inline constexpr const char* kLatexPartBreak = "\\par\\penalty0\\relax\\ifdim\\pagetotal>0.45\\pagegoal\\clearpage\\fi\n";

/// A centred figure kept on the page of the heading or sentence before it, which introduces
/// it: a page may break before that text, never between it and the drawing (the center
/// environment invites a break there). The drawing and its caption (latex_figure_caption)
/// between the two; a plain group, as a fragment compiles in anyone's notes.
inline constexpr const char* kLatexFigureBegin = "\\par\\nopagebreak\\medskip\n{\\centering\\noindent\n";
inline constexpr const char* kLatexFigureEnd = "}\\par\\medskip\n";

/// A figure's numbered caption, under its drawing ("Figure 3: Velocity polygon"): the
/// figure counter stepped by hand rather than a float, so that the drawing stays where
/// the text refers to it and a fragment needs no package.
std::string latex_figure_caption(const std::string& text);

/// A number for math mode, `digits` significant ("1\cdot 10^{-5}" for 1e-05).
std::string latex_number(double value, int digits = 6);

/// Numbers as a document shows them, zero at the problem's scale as 0 (zero_at_scale,
/// engine/base/number_format): below 1e-12 of the larger of the mechanism's size for the
/// value's kind (ProblemScale) and `shown_with`, the largest magnitude shown with it (its
/// vector's components, its table column), so that round-off (1.00804e-16 m/s,
/// -6.6262e-15 deg) never reads as a value. Every number of the worked solution is
/// written through this.
class DocumentNumbers {
 public:
  explicit DocumentNumbers(const ConstraintSystem& system);
  /// `shown`: a value in the document's units (OutputScale: lengths in its unit, angles
  /// in degrees, angular rates in rad/s) of a quantity of `dimension` (length, angle,
  /// or number: no size of its own) differentiated `order` times (0, 1, 2).
  std::string operator()(double shown, Dimension dimension, int order, int digits = 6, double shown_with = 0) const;
  /// A ratio of two of the mechanism's rates (omega_j / omega_driver): its scale is 1, the
  /// driver's own (the parallelogram's omega2/omega1 came out 1.96e-16).
  std::string ratio(double value, int digits = 6) const;
  /// A value read off a figure (a polygon's arrow): its four significant digits, written
  /// out below 10^7 as the formulas' values beside it are (78900, not 7.89\cdot 10^{4}
  /// beside 4950); round-off as 0.
  std::string read_off(double shown, Dimension dimension, int order) const;
  /// The value itself, 0 where it is round-off.
  double cleaned(double shown, Dimension dimension, int order, double shown_with = 0) const;

 private:
  ProblemScale problem_;
};

}  // namespace kinema
