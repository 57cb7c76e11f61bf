#include <kinema/engine/printers/latex/latex_names.hpp>

#include <cctype>
#include <set>
#include <sstream>

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

std::string latex_escape_text(const std::string& text) {
  std::string out;
  for (char c : text) {
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
      case '\n': case '\r': out += ' '; break;
      default: out += c;
    }
  }
  return out;
}

void check_latex_name(const std::string& latex, const std::string& context) {
  static const std::set<std::string> accents = {"dot", "ddot", "hat", "bar", "tilde", "vec", "mathrm",
                                                "mathit", "prime"};
  for (std::size_t i = 0; i < latex.size(); ++i) {
    const char c = latex[i];
    if (std::isalnum(static_cast<unsigned char>(c)) || std::string("_^{}' ,").find(c) != std::string::npos) continue;
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
    throw InputError(context + ": LaTeX name \"" + latex + "\" contains \"" + std::string(1, c) +
                     "\"; use letters, digits, _ ^ { } and Greek letters");
  }
}

// Top-level terms of a formula as written ("a*exp(I*t) - d" -> "a*exp(I*t)", "-d"),
// so the drawing follows the chain in the order the user wrote the loop.
std::vector<std::string> written_terms(const std::string& formula) {
  std::vector<std::string> terms;
  std::string current;
  int depth = 0;
  for (std::size_t i = 0; i < formula.size(); ++i) {
    const char c = formula[i];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    const bool sign = (c == '+' || c == '-') && depth == 0;
    // Not a sign of an exponent (1e-3) and not the first character.
    const bool exponent = i > 0 && (formula[i - 1] == 'e' || formula[i - 1] == 'E') && i > 1 &&
                          std::isdigit(static_cast<unsigned char>(formula[i - 2]));
    if (sign && !exponent && current.find_first_not_of(" \t") != std::string::npos) {
      terms.push_back(current);
      current.clear();
    }
    current += c;
  }
  if (current.find_first_not_of(" \t") != std::string::npos) terms.push_back(current);
  return terms;
}


GiNaC::exmap latex_symbols(const Mechanism& m, const Derivation& d) {
  GiNaC::exmap names;
  auto add = [&](const GiNaC::realsymbol& s, const std::string& latex) {
    names[s] = GiNaC::realsymbol(s.get_name(), latex);
  };
  for (const auto& p : d.closure.parameters) add(p, latex_symbol_name(p.get_name()));
  add(d.closure.input, latex_symbol_name(d.closure.input.get_name()));
  add(d.input_rate, latex_symbol_name(d.input_rate.get_name()));
  add(d.input_second_rate, latex_symbol_name(d.input_second_rate.get_name()));
  for (std::size_t i = 0; i < d.closure.unknowns.size(); ++i) {
    const std::string& given = m.unknowns[i].latex_name;
    if (!given.empty()) check_latex_name(given, m.unknowns[i].where.str() + ": unknown \"" + m.unknowns[i].name + "\"");
    add(d.closure.unknowns[i], given.empty() ? latex_symbol_name(m.unknowns[i].name) : given);
    add(d.rates[i], given.empty() ? latex_symbol_name(d.rates[i].get_name()) : "\\dot{" + given + "}");
    add(d.second_rates[i],
        given.empty() ? latex_symbol_name(d.second_rates[i].get_name()) : "\\ddot{" + given + "}");
  }
  return names;
}

std::string latex_exp(const GiNaC::ex& angle, const GiNaC::exmap& names) {
  const std::string a = to_latex(angle, names);
  return "e^{i" + (GiNaC::is_a<GiNaC::add>(angle) ? "(" + a + ")" : a) + "}";
}

std::string latex_column(const std::vector<GiNaC::ex>& entries, const GiNaC::exmap& names) {
  std::string text = "\\begin{bmatrix}";
  for (std::size_t i = 0; i < entries.size(); ++i) text += (i ? " \\\\ " : " ") + to_latex(entries[i], names);
  return text + " \\end{bmatrix}";
}

std::string latex_matrix(const GiNaC::matrix& matrix, const GiNaC::exmap& names) {
  std::string text = "\\begin{bmatrix}";
  for (unsigned i = 0; i < matrix.rows(); ++i) {
    for (unsigned j = 0; j < matrix.cols(); ++j) text += (j ? " & " : " ") + to_latex(matrix(i, j), names);
    text += i + 1 < matrix.rows() ? " \\\\" : " ";
  }
  return text + "\\end{bmatrix}";
}

std::string to_latex(const GiNaC::ex& e, const GiNaC::exmap& names) {
  std::ostringstream out;
  out << GiNaC::latex << e.subs(names);
  return out.str();
}

}  // namespace kinema
