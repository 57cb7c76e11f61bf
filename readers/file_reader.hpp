// What the readers of the three file forms share (vector loops: vector_loop_reader.cpp;
// joints and links: joints_reader.cpp; spatial frames: frames_reader.cpp): the file
// parsed and its text checked, and the reading every form does alike: keys in the order
// written, each value's file:line, strings, quantities with units, names, rates, the
// heading ([output], [parameters]) and the driver's motion. Internal to readers/: the
// public entry is readers/mechanism_file.hpp.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

// toml++ compiled into the readers (header-only mode, not Debian's shared build) so that
// the sanitizer and fuzzer builds instrument the parser too. It bounds nesting (256)
// and refuses integers that do not fit in 64 bits; toml11 3.7 did neither (issue 9:
// stack overflow at 5,880 nested arrays, a heap over-read on 3 bytes). It is given
// ASCII only (toml_ascii.hpp says why).
#define TOML_HEADER_ONLY 1
#define TOML_ENABLE_FORMATTERS 0
#include <toml++/toml.h>

#include "engine/base/source_location.hpp"
#include "engine/base/units.hpp"
#include "readers/mechanism.hpp"

namespace kinema::reading {

using Node = toml::node;

// One file's reading: every message names the file and the line of the value it is about.
class FileReader {
 public:
  explicit FileReader(std::string file) : file_(std::move(file)) {}

  /// The file's text parsed (syntax errors with line and column, `what` naming the file's
  /// kind) and every key and string checked (check_text).
  toml::table parse(const std::string& text, const std::string& what = "mechanism file") const;

  // Every key and string of the file, before anything reads them: no character that
  // controls how text is shown (engine/base/user_text.hpp) — ESC and the like would
  // reach the terminal, U+202E reorders a C++ comment or a message. Line breaks only in
  // the title and the description (`multi_line`); tabs anywhere.
  void check_text(const Node& node, const std::string& key, bool multi_line) const;

  // Where a value was written, and reading a table's entry.
  SourceLocation where(const Node& value) const { return {file_, static_cast<int>(value.source().begin.line)}; }
  static bool has(const Node& table, const std::string& key) { return table.as_table()->contains(key); }
  static const Node& at(const Node& table, const std::string& key) { return *table.as_table()->get(key); }

  // InputError "file:line: what contains ..." for a control character, a bidirectional
  // control, or a line break where `multi_line` is false.
  void check_string(const std::string& text, const SourceLocation& at, const std::string& what,
                    bool multi_line) const;
  // InputError at the value's line.
  [[noreturn]] void fail(const Node& value, const std::string& message) const;
  // Table entries in the order they were written (TOML tables are unordered maps).
  std::vector<std::pair<std::string, const Node*>> ordered(const Node& table) const;
  // Refuses a key that is not allowed, naming those that are.
  void check_keys(const Node& table, std::initializer_list<const char*> allowed, const std::string& context) const;
  // A string, or a number written bare (as its text).
  std::string string_value(const Node& value, const std::string& key) const;
  std::string optional_string(const Node& table, const std::string& key, const std::string& fallback) const;
  // A value with its unit; UnitError at its line.
  Quantity quantity(const Node& value, const std::string& key) const;
  // A quantity that must have the given dimension (a bare number is taken as SI of it).
  double quantity_of(const Node& value, const std::string& key, Dimension expected) const;
  // ASCII letters, digits and _, starting with a letter: a name is safe in formulas,
  // CSV headers, LaTeX comments and generated code alike.
  static bool is_identifier(const std::string& name);
  // Names of loops and points: identifiers (they head CSV columns and LaTeX text).
  void check_name(const Node& value, const std::string& name, const std::string& what) const;
  // Names of symbols in formulas: identifiers that GiNaC's parser gives no meaning of its own.
  void check_identifier(const Node& value, const std::string& name, const std::string& what) const;
  // A driver rate: past kMaxRate (SI) the squared rates in the accelerations overflow
  // long before any machine turns that fast, so it is refused rather than reported as
  // non-finite results.
  double bounded_rate(const Node& value, const std::string& key, Dimension dimension) const;
  // An optional rate name: a symbol in formulas, so an identifier that is not reserved.
  std::string optional_name(const Node& table, const std::string& key) const;
  // A section the form needs: missing, the message points to the file format.
  const Node& required_table(const Node& root, const std::string& key) const;
  void read_output(const Node& root, Mechanism& mechanism) const;
  void read_parameters(const Node& root, Mechanism& mechanism) const;
  // The driver's values, rate and second rate, as [input] and [driver] give them.
  void read_motion(const Node& table, const std::string& section, Input& input) const;

  // The optional [problem] table (problem_reader.cpp), the same in every form.
  void read_problem(const Node& root, Mechanism& mechanism) const;

  // Title, description, [output], [parameters] and [problem]: every form opens alike.
  void read_heading(const Node& root, Mechanism& mechanism) const;

 protected:
  std::string file_;
};

/// A text file read whole, for every file kinema reads (mechanism files, answers files,
/// class tables): InputError for a directory, a file that cannot be opened, or one larger
/// than max_bytes (`what` names its kind: "answers file").
std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& what);

// The three forms, each from a parsed and checked file (`mechanism` holds its source_file).
void read_vector_loops(const std::string& file, const Node& root, Mechanism& mechanism);
void read_joints_and_links(const std::string& file, const Node& root, Mechanism& mechanism);
void read_spatial_frames(const std::string& file, const Node& root, Mechanism& mechanism);

}  // namespace kinema::reading
