#include "linkages/vector_loop_file.hpp"

#include <sstream>

#include "engine/base/errors.hpp"
#include "engine/base/number_format.hpp"
#include "engine/base/user_text.hpp"
#include "linkages/linkage_loops.hpp"

namespace kinema {
namespace {

// A TOML basic string: quotes and backslashes escaped, line breaks and tabs as \n, \t,
// other control characters and bidirectional controls as \uXXXX (a raw line break would
// end the string: a multi-line title or description made the file unreadable).
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size(); ++i) {
    const std::size_t start = i;
    const unsigned long c = next_code_point(text, i);
    if (c == '"' || c == '\\') out += std::string("\\") + static_cast<char>(c);
    else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (is_control_character(c) || is_bidi_control(c)) out += "\\u" + code_point_name(c).substr(2);
    else out.append(text, start, i + 1 - start);
  }
  return out + "\"";
}

}  // namespace

std::string vector_loop_file(const Mechanism& written, const ConstraintSystem& system) {
  if (written.chain) {  // its input, unknowns and loops are empty: it was written as an empty mechanism
    throw InputError(written.source_file + ": kinema loops writes a planar mechanism as vector loops; this file is a "
                     "spatial chain ([frames] and [variables]), which they cannot describe. Its equations: kinema "
                     "derive " + written.source_file);
  }
  const Mechanism m = written.linkage ? linkage_loops(written).loops : written;
  std::ostringstream out;
  out << "# " << one_line(m.title) << ": vector loops";
  if (written.linkage) out << " written by kinema from the joints and links of " << one_line(m.source_file);
  out << "\ntitle = " << quoted(m.title) << "\n";
  if (!m.description.empty()) out << "description = " << quoted(m.description) << "\n";
  if (!m.parameters.empty()) {
    out << "\n[parameters]\n";
    for (const Parameter& p : m.parameters) out << p.name << " = " << quoted(p.text) << "\n";
  }
  // 15 digits: what a reader expects to see ("30 deg", not 29.999999999999996), and
  // within 1e-15 of the value.
  const auto angle_or_length = [](double si, Dimension d) {
    return d == Dimension::angle ? format_significant(to_degrees(si), 15) + " deg" : format_significant(si, 15) + " m";
  };
  const Input& input = m.input;
  out << "\n[input]\nname = " << quoted(input.name) << "\n";
  if (input.values.size() == 1) out << "value = " << quoted(angle_or_length(input.values[0], input.dimension)) << "\n";
  if (input.values.size() > 1) {
    out << "values = [";
    for (std::size_t k = 0; k < input.values.size(); ++k)
      out << (k ? ", " : "") << quoted(angle_or_length(input.values[k], input.dimension));
    out << "]\n";
  }
  const Dimension rate = rate_dimension(input.dimension);
  // The driver's rates as the joints-and-links file wrote them ("60 rpm"), so that the
  // vector-loop file's documents state them so too; in SI where none was written.
  out << "rate = "
      << quoted(!input.rate_text.empty() ? input.rate_text
                                         : format_significant(input.rate, 15) + (rate == Dimension::angular_velocity ? " rad/s" : " m/s"))
      << "\n";
  out << "second_rate = "
      << quoted(!input.second_rate_text.empty()
                    ? input.second_rate_text
                    : format_significant(input.second_rate, 15) + (rate == Dimension::angular_velocity ? " rad/s^2" : " m/s^2"))
      << "\n";
  if (!input.rate_name.empty()) out << "rate_name = " << quoted(input.rate_name) << "\n";
  if (!input.second_rate_name.empty()) out << "second_rate_name = " << quoted(input.second_rate_name) << "\n";
  out << "\n[unknowns]\n";
  for (std::size_t i = 0; i < m.unknowns.size(); ++i) {
    // The guess the system has: a dyad's stated assembly moves the sketch's (engine/numeric/assemblies).
    const Unknown& u = m.unknowns[i];
    const double guess = i < system.unknowns.size() ? system.unknowns[i].guess : u.guess;
    out << u.name << " = { guess = " << quoted(angle_or_length(guess, u.dimension));
    if (!u.rate_name.empty()) out << ", rate_name = " << quoted(u.rate_name);
    if (!u.second_rate_name.empty()) out << ", second_rate_name = " << quoted(u.second_rate_name);
    if (!u.latex_name.empty()) out << ", latex = " << quoted(u.latex_name);
    out << " }\n";
  }
  out << "\n[loops]\n";
  for (const Loop& loop : m.loops) {
    if (loop.complex_formula.empty()) out << loop.name << " = { x = " << quoted(loop.x_formula) << ", y = " << quoted(loop.y_formula) << " }\n";
    else out << loop.name << " = " << quoted(loop.complex_formula) << "\n";
  }
  if (!m.points.empty()) {
    out << "\n[points]\n";
    for (const Point& p : m.points) out << p.name << " = " << quoted(p.formula) << "\n";
  }
  if (m.output.length != "m") out << "\n[output]\nlength = " << quoted(m.output.length) << "\n";
  return out.str();
}

}  // namespace kinema
