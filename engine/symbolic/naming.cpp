#include <kinema/engine/symbolic/naming.hpp>

#include <algorithm>
#include <cctype>
#include <set>

#include <kinema/engine/errors.hpp>

namespace kinema {
namespace {

const std::set<std::string>& greek_letters() {
  static const std::set<std::string> letters = {
      "alpha", "beta",  "gamma", "delta", "epsilon", "zeta", "eta",   "theta", "iota",  "kappa",
      "lambda", "mu",   "nu",    "xi",    "pi",      "rho",  "sigma", "tau",   "upsilon", "phi",
      "chi",   "psi",   "omega", "Gamma", "Delta",   "Theta", "Lambda", "Xi",  "Pi",    "Sigma",
      "Upsilon", "Phi", "Psi",   "Omega", "varphi",  "vartheta", "varepsilon"};
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

void check_latex_name(const std::string& latex, const std::string& context) {
  static const std::set<std::string> accents = {"dot", "ddot", "hat", "bar", "tilde", "vec", "mathrm",
                                                "mathit", "prime"};
  // No ^ at all: TeX's ^^5c notation would rebuild any command from plain characters.
  int depth = 0;
  for (std::size_t i = 0; i < latex.size(); ++i) {
    const char c = latex[i];
    const bool ascii_alnum = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9');
    if (c == '{') ++depth;
    if (c == '}' && --depth < 0) break;
    if (ascii_alnum || std::string("_{}' ,").find(c) != std::string::npos) continue;
    if (c == '\\') {
      std::size_t j = i + 1;
      while (j < latex.size() && std::isalpha(static_cast<unsigned char>(latex[j]))) ++j;
      const std::string command = latex.substr(i + 1, j - i - 1);
      if (greek_letters().count(command) || accents.count(command)) {
        i = j - 1;
        continue;
      }
      throw InputError(context + ": LaTeX name \"" + latex + "\" uses \\" + command +
                       "; only Greek letters and \\dot \\ddot \\hat \\bar \\tilde \\vec \\mathrm "
                       "\\mathit \\prime are allowed");
    }
    throw InputError(context + ": LaTeX name \"" + latex + "\" contains \"" +
                     (static_cast<unsigned char>(c) < 0x20 ? std::string("a control character") : std::string(1, c)) +
                     "\"; use letters, digits, _ { } ' and Greek letters");
  }
  if (depth != 0) {
    throw InputError(context + ": LaTeX name \"" + latex + "\" has unbalanced braces { }; close each { with }");
  }
}

}  // namespace kinema
