#include "engine/printers/web/mathml.hpp"

#include <cctype>
#include <map>
#include <vector>

namespace kinema {
namespace {

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

const std::map<std::string, std::string>& greek() {
  static const std::map<std::string, std::string> letters = {
      {"alpha", "α"}, {"beta", "β"},   {"gamma", "γ"}, {"delta", "δ"}, {"epsilon", "ϵ"}, {"varepsilon", "ε"},
      {"zeta", "ζ"},  {"eta", "η"},    {"theta", "θ"}, {"vartheta", "ϑ"}, {"iota", "ι"}, {"kappa", "κ"},
      {"lambda", "λ"}, {"mu", "μ"},    {"nu", "ν"},    {"xi", "ξ"},    {"pi", "π"},      {"rho", "ρ"},
      {"sigma", "σ"}, {"tau", "τ"},    {"upsilon", "υ"}, {"phi", "ϕ"}, {"varphi", "φ"},  {"chi", "χ"},
      {"psi", "ψ"},   {"omega", "ω"},  {"Gamma", "Γ"}, {"Delta", "Δ"}, {"Theta", "Θ"},   {"Lambda", "Λ"},
      {"Xi", "Ξ"},    {"Pi", "Π"},     {"Sigma", "Σ"}, {"Phi", "Φ"},   {"Psi", "Ψ"},     {"Omega", "Ω"}};
  return letters;
}

const std::map<std::string, std::string>& operators() {
  static const std::map<std::string, std::string> symbols = {
      {"times", "×"}, {"cdot", "⋅"}, {"circ", "∘"}, {"pm", "±"}, {"mp", "∓"}, {"to", "→"},
      {"leq", "≤"},  {"geq", "≥"},  {"neq", "≠"},  {"approx", "≈"}, {"infty", "∞"}, {"partial", "∂"},
      {"rightarrow", "→"}, {"nabla", "∇"}, {"sum", "∑"}, {"prime", "′"}, {"surd", "√"}, {"lvert", "|"}, {"rvert", "|"},
      {"vert", "|"}};
  return symbols;
}

// Spacing commands and their widths (em).
const std::map<std::string, std::string>& spaces() {
  static const std::map<std::string, std::string> widths = {
      {",", "0.1667em"}, {":", "0.2222em"}, {";", "0.2778em"}, {" ", "0.3333em"}, {"quad", "1em"}, {"qquad", "2em"}};
  return widths;
}

// How letters are set: italic (math's default), upright (\mathrm, \mathbf), bold.
struct Style {
  bool upright = false, bold = false;
};

// One element as it is; several (or none) in an <mrow>, which the script and fraction
// elements need (one child each).
std::string group(const std::string& elements, const std::string& attributes = "") {
  int depth = 0, children = 0;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    if (elements[i] != '<') continue;
    const bool closing = i + 1 < elements.size() && elements[i + 1] == '/';
    if (!closing && depth == 0) ++children;
    depth += closing ? -1 : 1;
  }
  if (children == 1 && attributes.empty()) return elements;
  return "<mrow" + attributes + ">" + elements + "</mrow>";
}

class MathReader {
 public:
  MathReader(const std::string& text, std::size_t begin, std::size_t end) : s_(text), i_(begin), end_(end) {}

  /// Atoms up to the end, a closing brace, a column (&) or a row (\\) break.
  std::string list(Style style = {}) {
    std::string out, last;
    while (true) {
      skip_space();
      if (i_ >= end_ || s_[i_] == '}' || s_[i_] == '&' || starts("\\\\") || starts("\\end{")) break;
      if (s_[i_] == '^' || s_[i_] == '_') {
        last = scripts(last, style);
        continue;
      }
      out += last;
      last = atom(style);
    }
    return out + last;
  }

  bool at_end() { skip_space(); return i_ >= end_; }
  bool starts(const char* text) const { return s_.compare(i_, std::char_traits<char>::length(text), text) == 0 && i_ < end_; }
  void expect(char c) {
    skip_space();
    if (i_ >= end_ || s_[i_] != c) throw MathmlError(std::string("MathML: expected '") + c + "' at " + context());
    ++i_;
  }
  std::size_t position() const { return i_; }
  void skip(std::size_t n) { i_ += n; }

  /// The rows of a table up to \end{name}: its cells split at & and rows at \\ (an empty
  /// last row left out), each cell aligned as align* aligns it.
  std::string table(const std::string& name) {
    std::string rows;
    while (true) {
      std::vector<std::string> cells{list()};
      while (!at_end() && s_[i_] == '&') {
        ++i_;
        cells.push_back(list());
      }
      const bool empty = cells.size() == 1 && cells[0].empty();
      if (!empty) {
        rows += "<mtr>";
        for (const std::string& cell : cells) rows += "<mtd>" + cell + "</mtd>";
        rows += "</mtr>";
      }
      if (starts("\\\\")) {
        i_ += 2;
        continue;
      }
      const std::string end = "\\end{" + name + "}";
      if (s_.compare(i_, end.size(), end) != 0) throw MathmlError("MathML: " + name + " not closed at " + context());
      i_ += end.size();
      return "<mtable class=\"" + (name == "align*" ? std::string("align") : name) + "\">" + rows + "</mtable>";
    }
  }

 private:
  const std::string& s_;
  std::size_t i_, end_;

  std::string context() const { return "\"" + s_.substr(i_, 40) + "\""; }

  void skip_space() {
    while (i_ < end_ && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }

  std::string scripts(const std::string& base, Style style) {
    std::string sub, sup;
    while (i_ < end_ && (s_[i_] == '^' || s_[i_] == '_')) {
      const char which = s_[i_++];
      (which == '^' ? sup : sub) = group(argument(style));
      skip_space();
    }
    const std::string b = group(base);
    if (!sub.empty() && !sup.empty()) return "<msubsup>" + b + sub + sup + "</msubsup>";
    if (!sub.empty()) return "<msub>" + b + sub + "</msub>";
    return "<msup>" + b + sup + "</msup>";
  }

  // A command's or a script's argument: a braced group or one token.
  std::string argument(Style style) {
    skip_space();
    if (i_ < end_ && s_[i_] == '{') {
      ++i_;
      std::string inside = list(style);
      expect('}');
      return inside;
    }
    return atom(style);
  }

  // The text of a braced argument as written (\text, \mathit): its escapes undone.
  std::string braced_text() {
    expect('{');
    std::string text;
    int depth = 0;
    while (i_ < end_ && (s_[i_] != '}' || depth > 0)) {
      if (s_[i_] == '\\' && i_ + 1 < end_ && std::string("_&%#${}").find(s_[i_ + 1]) != std::string::npos) ++i_;
      else if (s_[i_] == '{') ++depth;
      else if (s_[i_] == '}') --depth;
      text += s_[i_++];
    }
    expect('}');
    return text;
  }

  std::string identifier(const std::string& text, Style style, bool single) {
    std::string attributes;
    if (style.upright && single) attributes += " mathvariant=\"normal\"";
    if (style.bold) attributes += " class=\"bold\"";
    return "<mi" + attributes + ">" + escaped(text) + "</mi>";
  }

  std::string atom(Style style) {
    skip_space();
    const char c = s_[i_];
    if (c == '{') {
      ++i_;
      std::string inside = list(style);
      expect('}');
      return group(inside);
    }
    if (c == '\\') return command(style);
    if (std::isalpha(static_cast<unsigned char>(c))) {
      // Upright letters run together into one name (rad, rel); italic ones are each a variable.
      std::size_t n = 1;
      if (style.upright)
        while (i_ + n < end_ && std::isalpha(static_cast<unsigned char>(s_[i_ + n]))) ++n;
      const std::string name = s_.substr(i_, n);
      i_ += n;
      return identifier(name, style, n == 1);
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      std::size_t n = 1;
      while (i_ + n < end_ && (std::isdigit(static_cast<unsigned char>(s_[i_ + n])) || s_[i_ + n] == '.')) ++n;
      const std::string number = s_.substr(i_, n);
      i_ += n;
      return std::string("<mn") + (style.bold ? " class=\"bold\"" : "") + ">" + number + "</mn>";
    }
    ++i_;
    if (c == '-') return "<mo>−</mo>";
    if (c == '~') return "<mspace width=\"0.3333em\"></mspace>";
    if (c == '\'') return "<mo>′</mo>";
    if (std::string("+=()[],/|:;<>!*").find(c) != std::string::npos) return "<mo>" + escaped(std::string(1, c)) + "</mo>";
    throw MathmlError(std::string("MathML: '") + c + "' is not read at " + context());
  }

  std::string command(Style style) {
    ++i_;  // the backslash
    if (i_ >= end_) throw MathmlError("MathML: a backslash at the end");
    std::string name;
    if (std::isalpha(static_cast<unsigned char>(s_[i_]))) {
      while (i_ < end_ && std::isalpha(static_cast<unsigned char>(s_[i_]))) name += s_[i_++];
    } else {
      name = s_[i_++];
    }
    if (const auto space = spaces().find(name); space != spaces().end())
      return "<mspace width=\"" + space->second + "\"></mspace>";
    if (name.size() == 1 && std::string("_&%#${}").find(name[0]) != std::string::npos)
      return "<mo>" + escaped(name) + "</mo>";
    if (const auto letter = greek().find(name); letter != greek().end()) {
      const bool capital = std::isupper(static_cast<unsigned char>(name[0]));
      return identifier(letter->second, Style{capital || style.upright, style.bold}, true);
    }
    if (const auto symbol = operators().find(name); symbol != operators().end()) return "<mo>" + symbol->second + "</mo>";
    if (name == "sin" || name == "cos" || name == "tan" || name == "exp" || name == "log" || name == "ln" || name == "arcsin" ||
        name == "arccos" || name == "arctan" || name == "sinh" || name == "cosh" || name == "tanh")
      return "<mspace width=\"0.1667em\"></mspace><mi>" + name + "</mi><mo>&#x2061;</mo><mspace width=\"0.1667em\"></mspace>";
    if (name == "operatorname")
      return "<mspace width=\"0.1667em\"></mspace><mi>" + escaped(braced_text()) + "</mi><mo>&#x2061;</mo>";
    if (name == "sqrt") return "<msqrt>" + argument(style) + "</msqrt>";
    if (name == "ensuremath") return group(argument(style));
    if (name == "mathit") return "<mi class=\"it\">" + escaped(braced_text()) + "</mi>";
    if (name == "text") return "<mtext>" + escaped(braced_text()) + "</mtext>";
    if (name == "mathrm") return group(argument(Style{true, style.bold}));
    if (name == "mathbf") return group(argument(Style{true, true}));
    if (name == "boldsymbol") return group(argument(Style{style.upright, true}));
    if (name == "hat" || name == "dot" || name == "ddot" || name == "vec" || name == "tilde" || name == "bar") {
      const std::map<std::string, const char*> accents = {{"hat", "^"}, {"dot", "˙"}, {"ddot", "¨"},
                                                          {"vec", "→"}, {"tilde", "~"}, {"bar", "¯"}};
      const char* accent = accents.at(name);
      return "<mover accent=\"true\">" + group(argument(style)) + "<mo>" + accent + "</mo></mover>";
    }
    if (name == "frac" || name == "tfrac") {
      const std::string numerator = argument(style);
      const std::string denominator = argument(style);
      // \frac in a display sets its parts as a display does; \tfrac as text does.
      const std::string parts = name == "frac" ? " displaystyle=\"true\"" : "";
      return "<mrow displaystyle=\"" + std::string(name == "frac" ? "true" : "false") + "\"><mfrac>" + group(numerator, parts) +
             group(denominator, parts) + "</mfrac></mrow>";
    }
    if (name == "boxed") return "<mrow class=\"boxed\">" + argument(style) + "</mrow>";
    if (name == "bigl" || name == "bigr" || name == "bigm" || name == "left" || name == "right" || name == "big") {
      skip_space();
      if (i_ < end_ && s_[i_] == '.') {  // \right. : no delimiter
        ++i_;
        return "";
      }
      return atom(style);
    }
    if (name == "begin") {
      const std::string environment = braced_text();
      if (environment != "bmatrix" && environment != "pmatrix" && environment != "matrix")
        throw MathmlError("MathML: the environment " + environment + " is not read");
      const std::string inside = table(environment);
      if (environment == "matrix") return inside;
      const bool square = environment == "bmatrix";
      return std::string("<mrow><mo>") + (square ? "[" : "(") + "</mo>" + inside + "<mo>" + (square ? "]" : ")") + "</mo></mrow>";
    }
    throw MathmlError("MathML: the command \\" + name + " is not read");
  }
};

// A paragraph's text with its inline $...$, as HTML.
std::string text_with_math(const std::string& text) {
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    if (text[i] == '$') {
      const std::size_t close = text.find('$', i + 1);
      if (close == std::string::npos) throw MathmlError("MathML: an inline formula not closed: " + text.substr(i, 40));
      MathReader reader(text, i + 1, close);
      const std::string inside = reader.list();
      if (!reader.at_end()) throw MathmlError("MathML: an inline formula read in part: " + text.substr(i, 40));
      out += "<math>" + inside + "</math>";
      i = close + 1;
    } else if (text[i] == '\\' && i + 1 < text.size() && std::string("_&%#${}").find(text[i + 1]) != std::string::npos) {
      out += escaped(std::string(1, text[i + 1]));
      i += 2;
    } else if (text[i] == '\\') {
      std::size_t end = i + 1;
      while (end < text.size() && std::isalpha(static_cast<unsigned char>(text[end]))) ++end;
      const std::string name = text.substr(i + 1, end - i - 1);
      static const std::map<std::string, std::string> characters = {
          {"textless", "<"}, {"textgreater", ">"}, {"textbar", "|"}, {"textbackslash", "\\"},
          {"textasciitilde", "~"}, {"textasciicircum", "^"}};
      if (const auto character = characters.find(name); character != characters.end()) {
        out += escaped(character->second);
        i = end;
        if (i + 1 < text.size() && text[i] == '{' && text[i + 1] == '}') i += 2;
        continue;
      }
      if (name != "noindent" && name != "par" && name != "begingroup" && name != "endgroup" && name != "allowdisplaybreaks")
        throw MathmlError("MathML: the text command \\" + name + " is not read");
      i = end;
      while (i < text.size() && text[i] == ' ') ++i;  // the space that ends a command's name
    } else {
      out += escaped(std::string(1, text[i]));
      ++i;
    }
  }
  return out;
}

// The text between formulas: a paragraph at each \\ or \par or blank line.
std::string paragraphs(const std::string& text) {
  std::string out, current;
  const auto flush = [&]() {
    std::size_t a = current.find_first_not_of(" \t\n"), b = current.find_last_not_of(" \t\n");
    if (a != std::string::npos) {
      const std::string html = text_with_math(current.substr(a, b - a + 1));
      if (html.find_first_not_of(" \t\n") != std::string::npos) out += "<p>" + html + "</p>\n";
    }
    current.clear();
  };
  bool in_math = false;  // inside $...$, where \\ is a formula's row, not a line's end
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '\\' && i + 1 < text.size() && !in_math && text[i + 1] == '$') {
      current += text.substr(i, 2);
      i += 2;
    } else if (text[i] == '$') {
      in_math = !in_math;
      current += text[i++];
    } else if (in_math) {
      current += text[i++];
    } else if (text.compare(i, 2, "\\\\") == 0) {
      flush();
      i += 2;
    } else if (text.compare(i, 4, "\\par") == 0 && (i + 4 >= text.size() || !std::isalpha(static_cast<unsigned char>(text[i + 4])))) {
      flush();
      i += 4;
    } else if (text.compare(i, 2, "\n\n") == 0) {
      flush();
      i += 2;
    } else {
      current += text[i++];
    }
  }
  flush();
  return out;
}

// The document without its comments (% to the end of the line, \% kept).
std::string without_comments(const std::string& latex) {
  std::string out;
  for (std::size_t i = 0; i < latex.size(); ++i) {
    if (latex[i] == '\\' && i + 1 < latex.size()) {
      out += latex[i];
      out += latex[++i];
    } else if (latex[i] == '%') {
      while (i < latex.size() && latex[i] != '\n') ++i;
      out += '\n';
    } else {
      out += latex[i];
    }
  }
  return out;
}

}  // namespace

std::string mathml_of_latex(const std::string& latex) {
  const std::string text = without_comments(latex);
  const std::string begin = "\\begin{align*}";
  std::string out;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t block = text.find(begin, i);
    out += paragraphs(text.substr(i, block == std::string::npos ? std::string::npos : block - i));
    if (block == std::string::npos) break;
    MathReader reader(text, block + begin.size(), text.size());
    out += "<math display=\"block\">" + reader.table("align*") + "</math>\n";
    i = reader.position();
  }
  return out;
}

}  // namespace kinema
