// Zero at the problem's scale prints 0 (issue 45): in every view of numbers for people, of
// every sample, no value printed is below 1e-12 of the largest magnitude of its column (the
// numbers shown together for one quantity: a table column, a vector's components) unless it
// is exactly 0. The views read back as printed: the text table (kinema eval), the worked
// solution (kinema latex: its tables, vectors and figures; a problem set's keys), the
// derivation (kinema derive: a chain's vectors) and the page's drawing data (kinema page). The page's readout is checked
// in the browser (tests/browser/page_test.js). CSV, JSON and npy are data: the values as solved.
#include <doctest/doctest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace {

// Numbers shown together, and where (for the message); `size`, where given, the size they
// are drawn at instead of their largest.
struct Group {
  std::string where;
  std::vector<double> values;
  double size = -1;
};

// Each value of a group that is below 1e-12 of the group's largest magnitude (its size) and not 0.
std::vector<std::string> round_off_shown(const std::vector<Group>& groups) {
  std::vector<std::string> found;
  for (const Group& g : groups) {
    double largest = g.size;
    if (largest < 0)
      for (double v : g.values) largest = std::max(largest, std::fabs(v));
    for (double v : g.values) {
      if (v == 0 || std::fabs(v) >= 1e-12 * largest) continue;
      std::ostringstream message;
      message << g.where << ": " << v << " beside " << largest;
      found.push_back(message.str());
    }
  }
  return found;
}

bool parse_number(const std::string& token, double& value) {
  static const std::regex number(R"(-?[0-9]+(\.[0-9]*)?(e[-+]?[0-9]+)?)");
  if (!std::regex_match(token, number)) return false;
  value = std::stod(token);
  return true;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// A line of the text table after its first word (a name): its numbers in order, and each
// parenthesised tuple of numbers ("(0, 1.64625)").
struct TableLine {
  std::vector<double> numbers;
  std::vector<std::vector<double>> tuples;
};

TableLine table_line(const std::string& line) {
  TableLine out;
  std::vector<double>* tuple = nullptr;
  std::string token;
  bool named = false;  // the first word is the row's name (a link's may be "5")
  const auto flush = [&] {
    double v;
    if (!token.empty() && named && parse_number(token, v)) {
      out.numbers.push_back(v);
      if (tuple) tuple->push_back(v);
    }
    if (!token.empty()) named = true;
    token.clear();
  };
  for (char c : line) {
    if (c == '(' || c == ')' || c == ',' || std::isspace(static_cast<unsigned char>(c))) {
      flush();
      if (c == '(') tuple = &out.tuples.emplace_back();
      if (c == ')') tuple = nullptr;
    } else {
      token += c;
    }
  }
  flush();
  out.tuples.erase(std::remove_if(out.tuples.begin(), out.tuples.end(), [](const auto& t) { return t.size() < 2; }),
                   out.tuples.end());
  return out;
}

// `kinema eval`'s table: within a block, the rows under a header (an indented line with no
// number after its first word) are a table; number k of each row is its column k; a tuple
// is a vector. Messages, the head and the input's line stand alone.
std::vector<Group> table_groups(const std::string& name, const std::string& text) {
  std::vector<Group> groups;
  std::map<std::size_t, Group> columns;  // of the current table
  std::string header;
  const auto end_table = [&] {
    for (auto& [k, g] : columns) groups.push_back(std::move(g));
    columns.clear();
  };
  const std::vector<std::string> lines = lines_of(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    const std::string where = name + " eval line " + std::to_string(i + 1) + " \"" + line + "\"";
    if (line.rfind("  ", 0) != 0) {
      end_table();
      continue;
    }
    const std::string trimmed = line.substr(line.find_first_not_of(' '));
    bool message = false;
    for (const char* prefix : {"SINGULAR:", "note:", "not assembled:", "branch:"}) message = message || trimmed.rfind(prefix, 0) == 0;
    if (message) {
      end_table();
      continue;
    }
    const TableLine row = table_line(line);
    if (row.numbers.empty()) {  // a header: a table begins
      end_table();
      header = trimmed;
      continue;
    }
    for (std::size_t k = 0; k < row.numbers.size(); ++k) {
      Group& column = columns[k];
      column.where = name + " eval, column " + std::to_string(k + 1) + " under \"" + header + "\", at line " +
                     std::to_string(i + 1);
      column.values.push_back(row.numbers[k]);
    }
    for (const auto& tuple : row.tuples) groups.push_back({where, tuple});
  }
  end_table();
  return groups;
}

// The text of LaTeX math with its numbers plain: 1.2\cdot 10^{-5} as 1.2e-5, sub- and
// superscripts (I_{01}, omega_{54}, ^{2}, ^{\circ}) and \multicolumn{2}{c} dropped.
std::string plain_numbers(std::string text) {
  text = std::regex_replace(text, std::regex(R"((-?[0-9.]+)\\cdot 10\^\{(-?[0-9]+)\})"), "$1e$2");
  text = std::regex_replace(text, std::regex(R"(\\multicolumn\{[^}]*\}\{[^}]*\})"), "");
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '_' && text[i] != '^') {
      out += text[i];
      continue;
    }
    if (i + 1 < text.size() && text[i + 1] == '{') {  // skip the braced group
      int depth = 0;
      std::size_t j = i + 1;
      for (; j < text.size(); ++j) {
        depth += text[j] == '{' ? 1 : text[j] == '}' ? -1 : 0;
        if (depth == 0) break;
      }
      i = j;
    } else {
      ++i;  // one character
    }
    out += ' ';
  }
  return out;
}

// The numbers of LaTeX text (plain_numbers'), each not part of a word (I01).
std::vector<double> latex_numbers(const std::string& text) {
  const std::string plain = plain_numbers(text);
  static const std::regex number(R"(-?[0-9]+(\.[0-9]+)?(e-?[0-9]+)?)");
  std::vector<double> out;
  for (auto it = std::sregex_iterator(plain.begin(), plain.end(), number); it != std::sregex_iterator(); ++it) {
    const auto at = static_cast<std::size_t>(it->position());
    if (at > 0 && (std::isalnum(static_cast<unsigned char>(plain[at - 1])) || plain[at - 1] == '.')) continue;
    out.push_back(std::stod(it->str()));
  }
  return out;
}

// A LaTeX document's numbers shown together: each tabular's columns (the cells at one place
// in its rows after \midrule), each math tuple "(a,\ b)" and each pmatrix.
std::vector<Group> latex_groups(const std::string& name, const std::string& text) {
  std::vector<Group> groups;
  const std::vector<std::string> lines = lines_of(text);
  std::map<std::size_t, Group> columns;
  bool in_body = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (line.find("\\midrule") != std::string::npos) {
      in_body = true;
      continue;
    }
    if (line.find("\\bottomrule") != std::string::npos || line.find("\\end{tabular}") != std::string::npos) {
      for (auto& [k, g] : columns) groups.push_back(std::move(g));
      columns.clear();
      in_body = false;
      continue;
    }
    if (!in_body || line.find("\\addlinespace") == 0) continue;
    // Cells: split at & outside braces.
    std::vector<std::string> cells(1);
    int depth = 0;
    for (char c : line) {
      depth += c == '{' ? 1 : c == '}' ? -1 : 0;
      if (c == '&' && depth == 0) cells.emplace_back();
      else cells.back() += c;
    }
    for (std::size_t k = 0; k < cells.size(); ++k) {
      const std::vector<double> numbers = latex_numbers(cells[k]);
      if (numbers.empty()) continue;
      Group& column = columns[k];
      column.where = name + " latex, tabular column " + std::to_string(k + 1) + " at line " + std::to_string(i + 1);
      column.values.insert(column.values.end(), numbers.begin(), numbers.end());
    }
  }
  static const std::regex tuple(R"(\(([^()]*,\\ [^()]*)\))"), matrix(R"(\\begin\{pmatrix\}(.*?)\\end\{pmatrix\})");
  for (const std::regex* vector : {&tuple, &matrix}) {
    for (auto it = std::sregex_iterator(text.begin(), text.end(), *vector); it != std::sregex_iterator(); ++it) {
      const std::vector<double> numbers = latex_numbers((*it)[1].str());
      if (numbers.size() >= 2) groups.push_back({name + " latex, vector " + it->str(), numbers});
    }
  }
  return groups;
}

// `kinema derive`'s vectors: "(a, b, c)" whose every part is a number.
std::vector<Group> derivation_groups(const std::string& name, const std::string& text) {
  std::vector<Group> groups;
  static const std::regex tuple(R"(\(([^()]*, [^()]*)\))");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), tuple); it != std::sregex_iterator(); ++it) {
    std::vector<double> numbers;
    std::string part;
    std::istringstream parts((*it)[1].str());
    bool all = true;
    while (std::getline(parts, part, ',')) {
      part.erase(0, part.find_first_not_of(' '));
      double v;
      all = all && parse_number(part, v);
      if (all) numbers.push_back(v);
    }
    if (all && numbers.size() >= 2) groups.push_back({name + " derive, vector " + it->str(), numbers});
  }
  return groups;
}

std::vector<std::string> sample_files() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(KINEMA_SAMPLES_DIR))
    if (entry.path().extension() == ".toml") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

void check_none(const std::vector<std::string>& found, std::size_t groups) {
  CHECK(groups > 0);
  for (const std::string& f : found) FAIL_CHECK("round-off printed as a value: " << f);
}

}  // namespace

TEST_CASE("numbers for people: every sample's table, worked solution and derivation print round-off beside a column as 0") {
  const std::vector<std::string> samples = sample_files();
  REQUIRE(samples.size() >= 18);
  for (const std::string& file : samples) {
    CAPTURE(file);
    const std::string path = kinema_test::sample(file);
    const kinema_test::CommandResult eval = kinema_test::run_kinema({"eval", path});
    REQUIRE(eval.exit_status == 0);
    const std::vector<Group> table = table_groups(file, eval.out);
    check_none(round_off_shown(table), table.size());
    const kinema_test::CommandResult latex = kinema_test::run_kinema({"latex", path});
    REQUIRE(latex.exit_status == 0);
    const std::vector<Group> document = latex_groups(file, latex.out);
    check_none(round_off_shown(document), document.size());
    const kinema_test::CommandResult derive = kinema_test::run_kinema({"derive", path});
    REQUIRE(derive.exit_status == 0);
    check_none(round_off_shown(derivation_groups(file, derive.out)), 1);
  }
  // A problem set's keys: each variant's worked solution and its answers.
  const std::string set = kinema_test::fresh_directory("numbers_for_people_set");
  const kinema_test::CommandResult problems = kinema_test::run_kinema(
      {"problems", kinema_test::sample("problem_4_4_set.toml"), "--count", "4", "--seed", "7", "-o", set});
  REQUIRE(problems.exit_status == 0);
  std::size_t keys = 0;
  for (const auto& entry : std::filesystem::directory_iterator(set)) {
    const std::string key = entry.path().filename().string();
    if (key.find("_key.tex") == std::string::npos) continue;
    CAPTURE(key);
    const std::vector<Group> document = latex_groups(key, kinema_test::read_file(entry.path().string()));
    check_none(round_off_shown(document), document.size());
    ++keys;
  }
  CHECK(keys == 4);
}

TEST_CASE("numbers for people: every sample's page writes its drawing's and centres' round-off as 0" * doctest::skip(kinema_test::kSanitized)) {
  for (const std::string& file : sample_files()) {
    CAPTURE(file);
    const std::string html = kinema_test::fresh_directory("numbers_for_people_pages") + "/" + file + ".html";
    const kinema_test::CommandResult page = kinema_test::run_kinema({"page", kinema_test::sample(file), "-o", html});
    REQUIRE(page.exit_status == 0);
    const std::string text = kinema_test::read_file(html);
    const std::string open = "id=\"kinema-data\">";
    const auto begin = text.find(open) + open.size();
    const nlohmann::json data = nlohmann::json::parse(text.substr(begin, text.find("</script>", begin) - begin));
    // The drawing over the run: one picture's numbers (each row [its pattern, its values]).
    Group drawing{file + " page drawing", {}};
    for (const auto& row : data["drawing"]["rows"])
      if (row.is_array())
        for (std::size_t k = 1; k < row.size(); ++k)
          if (row[k].is_number()) drawing.values.push_back(row[k].get<double>());
    // The centres are drawn on it: their coordinates at its size ([structure, Kennedy set, numbers];
    // a centre far off, near parallel lines, is no measure of the others).
    double largest = 0;
    for (double v : drawing.values) largest = std::max(largest, std::fabs(v));
    std::vector<Group> groups = {drawing};
    for (const auto& row : data["constructions"]["rows"]) {
      if (!row.is_object() || !row.contains("centres")) continue;
      Group centres{file + " page centres", {}, largest};
      for (std::size_t k = 2; k < row["centres"].size(); ++k)
        if (row["centres"][k].is_number()) centres.values.push_back(row["centres"][k].get<double>());
      groups.push_back(centres);
    }
    check_none(round_off_shown(groups), groups.size());
  }
}

TEST_CASE("numbers for people: the parallelogram's coupler that does not turn and rocker that turns as the crank print their zeros as 0") {
  // AB = CD, BC = AD (the file's comment): the coupler stays parallel to AD (theta2 = omega2
  // = alpha2 = 0) and CD turns with AB at its constant rate (omega3 = omega1, alpha3 = 0).
  // Their solved values are round-off, some of them (alpha3 = 3.4e-14 rad/s^2 at 75 deg)
  // with no larger value in their column: zero at the problem's scale (omega1^2) decides.
  const kinema_test::CommandResult eval = kinema_test::run_kinema(
      {"eval", kinema_test::sample("problem_4_1_parallelogram.toml"), "--angle", "30", "--angle", "75", "--angle", "250"});
  REQUIRE(eval.exit_status == 0);
  const std::regex coordinate(R"(^  (theta[23]) +(\S+) deg +omega[23] = (\S+) rad/s +alpha[23] = (\S+) rad/s\^2$)");
  const std::regex driver(R"(^phi = \S+ deg +omega1 = (\S+) rad/s)");
  std::string omega1;
  std::size_t checked = 0;
  for (const std::string& line : lines_of(eval.out)) {
    CAPTURE(line);
    std::smatch m;
    if (std::regex_search(line, m, driver)) omega1 = m[1];
    if (!std::regex_match(line, m, coordinate)) continue;
    REQUIRE(!omega1.empty());
    if (m[1] == "theta2") {
      CHECK(m[2] == "0");
      CHECK(m[3] == "0");
      CHECK(m[4] == "0");
    } else {
      CHECK(m[3] == omega1);
      CHECK(m[4] == "0");
    }
    ++checked;
  }
  CHECK(checked == 6);
}
