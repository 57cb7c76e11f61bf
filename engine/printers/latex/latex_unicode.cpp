#include "engine/printers/latex/latex_unicode.hpp"

#include <cstdio>
#include <map>

namespace kinema {
namespace {

// Greek, U+0391..U+03C9 (letters with no command of their own are their Latin twins).
const char* const kGreekUpper[] = {"A", "B", "\\Gamma", "\\Delta", "E", "Z", "H", "\\Theta", "I", "K", "\\Lambda",
                                   "M", "N", "\\Xi", "O", "\\Pi", "P", nullptr, "\\Sigma", "T", "\\Upsilon",
                                   "\\Phi", "X", "\\Psi", "\\Omega"};
const char* const kGreekLower[] = {"\\alpha", "\\beta", "\\gamma", "\\delta", "\\varepsilon", "\\zeta", "\\eta",
                                   "\\theta", "\\iota", "\\kappa", "\\lambda", "\\mu", "\\nu", "\\xi", "o", "\\pi",
                                   "\\rho", "\\varsigma", "\\sigma", "\\tau", "\\upsilon", "\\varphi", "\\chi",
                                   "\\psi", "\\omega"};

// Latin-1 letters U+00C0..U+00FF as accent commands (the kernel's, in any font encoding).
const char* const kLatin1Letters[] = {
    "\\`A", "\\'A", "\\^A", "\\~A", "\\\"A", "\\AA{}", "\\AE{}", "\\c{C}", "\\`E", "\\'E", "\\^E", "\\\"E", "\\`I",
    "\\'I", "\\^I", "\\\"I", "D", "\\~N", "\\`O", "\\'O", "\\^O", "\\~O", "\\\"O", "\\ensuremath{\\times}", "\\O{}",
    "\\`U", "\\'U", "\\^U", "\\\"U", "\\'Y", "Th", "\\ss{}", "\\`a", "\\'a", "\\^a", "\\~a", "\\\"a", "\\aa{}",
    "\\ae{}", "\\c{c}", "\\`e", "\\'e", "\\^e", "\\\"e", "\\`\\i{}", "\\'\\i{}", "\\^\\i{}", "\\\"\\i{}", "d", "\\~n",
    "\\`o", "\\'o", "\\^o", "\\~o", "\\\"o", "\\ensuremath{\\div}", "\\o{}", "\\`u", "\\'u", "\\^u", "\\\"u", "\\'y",
    "th", "\\\"y"};

const std::map<unsigned long, const char*>& others() {
  static const std::map<unsigned long, const char*> table = {
      {0x00A0, "~"}, {0x00A7, "\\S{}"}, {0x00A9, "\\copyright{}"}, {0x00B0, "\\ensuremath{^\\circ}"},
      {0x00B1, "\\ensuremath{\\pm}"}, {0x00B2, "\\ensuremath{^2}"}, {0x00B3, "\\ensuremath{^3}"},
      {0x00B5, "\\ensuremath{\\mu}"}, {0x00B6, "\\P{}"}, {0x00B7, "\\ensuremath{\\cdot}"},
      {0x00B9, "\\ensuremath{^1}"}, {0x00BD, "1/2"}, {0x0107, "\\'c"}, {0x010D, "\\v{c}"}, {0x011B, "\\v{e}"},
      {0x0141, "\\L{}"}, {0x0142, "\\l{}"}, {0x0144, "\\'n"}, {0x0151, "\\H{o}"}, {0x0159, "\\v{r}"},
      {0x0160, "\\v{S}"}, {0x0161, "\\v{s}"}, {0x0171, "\\H{u}"}, {0x017D, "\\v{Z}"}, {0x017E, "\\v{z}"},
      {0x03D1, "\\ensuremath{\\vartheta}"}, {0x03D5, "\\ensuremath{\\phi}"}, {0x2013, "--"}, {0x2014, "---"},
      {0x2018, "`"}, {0x2019, "'"}, {0x201C, "``"}, {0x201D, "''"}, {0x2026, "\\ldots{}"},
      {0x2032, "\\ensuremath{'}"}, {0x2190, "\\ensuremath{\\leftarrow}"}, {0x2192, "\\ensuremath{\\rightarrow}"},
      {0x2202, "\\ensuremath{\\partial}"}, {0x2207, "\\ensuremath{\\nabla}"}, {0x2208, "\\ensuremath{\\in}"},
      {0x2211, "\\ensuremath{\\sum}"}, {0x2212, "\\ensuremath{-}"}, {0x221A, "\\ensuremath{\\surd}"},
      {0x221E, "\\ensuremath{\\infty}"}, {0x2220, "\\ensuremath{\\angle}"}, {0x222B, "\\ensuremath{\\int}"},
      {0x2248, "\\ensuremath{\\approx}"}, {0x2260, "\\ensuremath{\\neq}"}, {0x2261, "\\ensuremath{\\equiv}"},
      {0x2264, "\\ensuremath{\\leq}"}, {0x2265, "\\ensuremath{\\geq}"}, {0x22C5, "\\ensuremath{\\cdot}"}};
  return table;
}

}  // namespace

std::string latex_for_code_point(unsigned long c) {
  if (c >= 0x0391 && c <= 0x03A9 && kGreekUpper[c - 0x0391]) {
    const std::string letter = kGreekUpper[c - 0x0391];
    return letter[0] == '\\' ? "\\ensuremath{" + letter + "}" : letter;
  }
  if (c >= 0x03B1 && c <= 0x03C9) {
    const std::string letter = kGreekLower[c - 0x03B1];
    return letter[0] == '\\' ? "\\ensuremath{" + letter + "}" : letter;
  }
  if (c >= 0x00C0 && c <= 0x00FF) return kLatin1Letters[c - 0x00C0];
  const auto found = others().find(c);
  if (found != others().end()) return found->second;
  char code[16];
  std::snprintf(code, sizeof code, "[U+%04lX]", c);
  return code;
}

}  // namespace kinema
