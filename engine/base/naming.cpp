#include "engine/base/naming.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "engine/base/errors.hpp"
#include "engine/base/user_text.hpp"

namespace kinema {
namespace {

const std::set<std::string>& greek_letters() {
  static const std::set<std::string> letters = {
      "alpha", "beta",  "gamma", "delta", "epsilon", "zeta", "eta",   "theta", "iota",  "kappa",
      "lambda", "mu",   "nu",    "xi",    "pi",      "rho",  "sigma", "tau",   "upsilon", "phi",
      "chi",   "psi",   "omega", "Gamma", "Delta",   "Theta", "Lambda", "Xi",  "Pi",    "Sigma",
      "Upsilon", "Phi", "Psi",   "Omega", "varphi",  "vartheta", "varepsilon", "varsigma", "varrho", "varpi"};
  return letters;
}

bool ends_with(const std::string& text, const std::string& suffix) {
  return text.size() > suffix.size() && text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// One part of a name (no underscores, no dot suffix).
std::string base_name(const std::string& name) {
  // A Greek word, possibly followed by a subscript: theta3, phi, omega2.
  for (std::size_t length = name.size(); length >= 2; --length) {
    const std::string head = name.substr(0, length);
    if (greek_letters().count(head)) {
      const std::string rest = name.substr(length);
      return "\\" + head + (rest.empty() ? "" : "_{" + rest + "}");
    }
  }
  if (name.size() == 1) return name;
  const bool all_upper = std::all_of(name.begin(), name.end(), [](char c) { return std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)); });
  if (all_upper) return "\\mathit{" + name + "}";  // a segment such as AB
  // One letter and a short subscript: r1, xE, La, yF.
  if (name.size() <= 3) return name.substr(0, 1) + "_{" + name.substr(1) + "}";
  return "\\mathit{" + name + "}";
}

}  // namespace

std::string latex_symbol_name(const std::string& name) {
  std::string core = name;
  std::string accent;
  if (ends_with(core, "_ddot")) {
    accent = "\\ddot";
    core = core.substr(0, core.size() - 5);
  } else if (ends_with(core, "_dot")) {
    accent = "\\dot";
    core = core.substr(0, core.size() - 4);
  }
  // theta2_given -> \theta_{2,\mathrm{given}}
  std::string qualifier;
  const auto underscore = core.find('_');
  if (underscore != std::string::npos && underscore > 0) {
    qualifier = core.substr(underscore + 1);
    core = core.substr(0, underscore);
    for (char& c : qualifier)
      if (c == '_') c = ' ';
  }
  std::string result = base_name(core);
  if (!qualifier.empty()) {
    const auto sub = result.find("_{");
    if (sub != std::string::npos) {
      result.insert(result.size() - 1, ",\\mathrm{" + qualifier + "}");
    } else {
      result += "_{\\mathrm{" + qualifier + "}}";
    }
  }
  if (!accent.empty()) {
    // The accent goes on the letter, not on its subscript: \dot{r}_{1}.
    const auto sub = result.find("_{");
    const std::string letter = sub == std::string::npos ? result : result.substr(0, sub);
    const std::string subscript = sub == std::string::npos ? "" : result.substr(sub);
    result = accent + "{" + letter + "}" + subscript;
  }
  return result;
}

std::string default_rate_name(const std::string& coordinate, int order) {
  for (const char* angle : {"theta", "phi"}) {
    const std::string prefix(angle);
    if (coordinate.size() > prefix.size() && coordinate.compare(0, prefix.size(), prefix) == 0) {
      return (order == 1 ? "omega" : "alpha") + coordinate.substr(prefix.size());
    }
  }
  return coordinate + (order == 1 ? "_dot" : "_ddot");
}

namespace {

// A LaTeX name from a file, read by its grammar (docs/mechanism-files.md, "LaTeX names"), so that it
// typesets wherever a printer puts it (\cos u, \dot{...}, (...)^{2}) and runs nothing but
// math typesetting:
//   name    := item*                                  (spaces between parts are ignored)
//   item    := nucleus [primes] ["_" script] [primes]   (one group of primes)
//   nucleus := letter | digit | "," | greek | \prime | accent "{" name "}" | "{" name "}"
//   script  := letter | digit | greek | \prime | "{" name "}"
// Nothing else: no ^ (TeX's ^^5c spells any command from plain characters), no other
// command, no $ & % # ~ \\ (so no \input, \write, \def, \catcode, \csname ...).
class LatexNameCheck {
 public:
  LatexNameCheck(const std::string& latex, const std::string& context) : latex_(latex), context_(context) {}

  void run() {
    name(0);
    if (i_ < latex_.size()) fail("has unbalanced braces { }; close each { with }");  // a } too many
    if (!nuclei_) fail("has nothing to typeset; write a letter, e.g. \\varphi_{2}");
    // amsmath cannot typeset an accent over two accents (\dot{\hat{x}_{\hat{y}}} stops
    // pdflatex), and kinema writes a coordinate's rate as \dot{name}.
    if (accents_ > 1) {
      fail("has more than one accent (\\dot \\ddot \\hat \\bar \\tilde \\vec); kinema writes a rate as "
           "\\dot{...} over the name, and amsmath cannot typeset an accent over two: keep one, e.g. \\hat{x}_{y}");
    }
  }

 private:
  static constexpr int kMaxBraceDepth = 8;  // braces within braces (README, Limits)
  const std::string& latex_;
  const std::string& context_;
  std::size_t i_ = 0;
  int nuclei_ = 0;
  int accents_ = 0;  // math accents (\mathrm and \mathit are fonts, not accents)

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(context_ + ": LaTeX name \"" + latex_ + "\" " + why);
  }
  bool at(char c) const { return i_ < latex_.size() && latex_[i_] == c; }
  void skip_spaces() {
    while (at(' ')) ++i_;
  }
  static bool letter_or_digit(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
  }

  void name(int depth) {
    for (skip_spaces(); i_ < latex_.size() && !at('}'); skip_spaces()) item(depth);
  }

  void item(int depth) {
    nucleus(depth);
    const bool primed = primes();
    if (at('_')) {
      ++i_;
      script(depth);
      skip_spaces();
      if (at('_')) fail("has two subscripts on one letter; write them as one: x_{1,2}");
      if (primes() && primed) fail("has primes before and after a subscript; write them together: x''_{1}");
    }
    skip_spaces();
    if (at('_')) fail("has two subscripts on one letter; write them as one: x_{1,2}");
    if (at('\'')) fail("has primes before and after a subscript; write them together: x''_{1}");
  }

  bool primes() {
    skip_spaces();
    if (!at('\'')) return false;
    while (at('\'')) ++i_;
    skip_spaces();
    return true;
  }

  // \name at i_ (i_ on the backslash): the command's name, i_ past it.
  std::string command() {
    std::size_t j = i_ + 1;
    while (j < latex_.size() && std::isalpha(static_cast<unsigned char>(latex_[j]))) ++j;
    const std::string command = latex_.substr(i_ + 1, j - i_ - 1);
    if (command.empty()) fail("has a \\ that starts no command (\\\\, \\, and the like are not allowed)");
    i_ = j;
    return command;
  }

  static bool is_symbol_command(const std::string& command) {
    return greek_letters().count(command) || command == "prime";
  }
  static bool is_accent(const std::string& command) {
    static const std::set<std::string> accents = {"dot", "ddot", "hat", "bar", "tilde", "vec", "mathrm", "mathit"};
    return accents.count(command) > 0;
  }

  void group(int depth) {
    if (depth + 1 > kMaxBraceDepth) fail("nests braces more than " + std::to_string(kMaxBraceDepth) + " deep");
    ++i_;  // {
    name(depth + 1);
    if (!at('}')) fail("has unbalanced braces { }; close each { with }");
    ++i_;
  }

  void nucleus(int depth) {
    const char c = latex_[i_];
    // Only what shows counts as something to typeset: "{}" or "\\hat{}" alone is nothing.
    if (letter_or_digit(c) || c == ',') {
      nuclei_ += c != ',';
      ++i_;
    } else if (c == '{') {
      group(depth);
    } else if (c == '\\') {
      const std::string name = command();
      if (is_symbol_command(name)) {
        ++nuclei_;
        return;
      }
      if (!is_accent(name)) {
        fail("uses \\" + name + "; only Greek letters (\\alpha ... \\Omega, \\varphi, ...), \\prime, and \\dot \\ddot "
             "\\hat \\bar \\tilde \\vec \\mathrm \\mathit with their argument in braces are allowed");
      }
      skip_spaces();
      if (!at('{')) fail("uses \\" + name + " without its argument: write \\" + name + "{x}");
      accents_ += name != "mathrm" && name != "mathit";
      group(depth);
    } else if (c == '_') {
      fail("has a subscript _ with nothing before it; write x_{1}");
    } else if (c == '\'') {
      fail("has a prime ' with nothing before it; write x'");
    } else if (c == '^') {
      fail("contains \"^\"; a superscript is not allowed (write a prime x' or a subscript x_{1})");
    } else {
      const bool control = is_control_character(static_cast<unsigned char>(c));
      const bool ascii = static_cast<unsigned char>(c) < 0x80;
      fail("contains " + (control ? std::string("a control character")
                          : ascii ? "\"" + std::string(1, c) + "\""
                                  : std::string("a character past ASCII (write Greek letters as \\alpha ...)")) +
           "; use letters, digits, _ { } ' , and Greek letters");
    }
  }

  void script(int depth) {
    skip_spaces();
    if (i_ >= latex_.size() || at('}')) fail("has a subscript _ with nothing after it; write x_{1}");
    const char c = latex_[i_];
    if (letter_or_digit(c)) {
      ++i_;
    } else if (c == '{') {
      group(depth);
    } else if (c == '\\') {
      const std::size_t start = i_;
      const std::string name = command();
      if (is_symbol_command(name)) return;
      i_ = start;
      if (is_accent(name)) fail("has \\" + name + " as a subscript without braces; write x_{\\" + name + "{y}}");
      nucleus(depth);  // says what is wrong with the command
    } else if (c == '_') {
      fail("has two subscripts on one letter; write them as one: x_{1,2}");
    } else {
      nucleus(depth);  // says what is wrong with the character (or takes "," for a subscript: not allowed)
      fail("has a subscript that is not a letter, a digit or {...}; write x_{1}");
    }
  }
};

}  // namespace

void check_latex_name(const std::string& latex, const std::string& context) {
  LatexNameCheck(latex, context).run();
}

}  // namespace kinema
