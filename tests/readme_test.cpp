// The README and docs/ say what is true: the README is a front door of at most 200
// lines whose links lead to files that exist, its first example output is the program's
// and its TOML snippets are lines of the samples they name; docs/library.md shows
// examples/library_usage.cpp as it is (that file is built against an installed kinema
// and run by the "package: ..." test) and the folders its "How it works" names exist.
// (docs/outputs.md's page table is checked by latex_pdf_test.)
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include "engine/model.hpp"

#include "tests/test_support.hpp"

namespace {

std::string project_file(const std::string& path) { return kinema_test::read_file(kinema_test::sample("../" + path)); }

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace

TEST_CASE("README: docs/library.md shows examples/library_usage.cpp verbatim, and the folders it names exist") {
  const std::string library = project_file("docs/library.md");
  const std::string example = project_file("examples/library_usage.cpp");
  REQUIRE(!library.empty());
  REQUIRE(example.find("#include <kinema/kinema.hpp>") != std::string::npos);
  REQUIRE(example.find(".rate(\"omega3\")") != std::string::npos);
  CHECK(library.find("```cpp\n" + example + "```") != std::string::npos);
  for (const char* folder : {"readers", "loops", "linkages", "chains", "engine/base", "engine/constraints",
                             "engine/symbolic", "engine/numeric", "engine/analysis", "engine/run", "engine/printers/text",
                             "engine/printers/web", "python",
                             "engine/printers/data", "engine/printers/latex", "engine/printers/code", "api/kinema", "cli"}) {
    CAPTURE(folder);
    CHECK(std::filesystem::is_directory(kinema_test::sample(std::string("../") + folder)));
  }
}

TEST_CASE("README's \"What it prints\" is what the command prints") {
  const std::string readme = project_file("README.md");
  const auto result = kinema_test::run_kinema({"eval", kinema_test::sample("problem_4_4_six_bar.toml")});
  REQUIRE(result.exit_status == 0);
  CHECK(readme.find("```\n$ ./build/kinema eval samples/problem_4_4_six_bar.toml\n" + result.out + "```") !=
        std::string::npos);
}

TEST_CASE("README is a front door: at most 200 lines, names the three forms, and its links lead to files") {
  const std::string readme = project_file("README.md");
  REQUIRE(!readme.empty());
  CHECK(lines_of(readme).size() <= 200);
  for (const char* form : {"vector loops", "joints and links", "spatial chain"}) {
    CAPTURE(form);
    CHECK(readme.find(form) != std::string::npos);
  }
  // Every link into docs/ (pages and pictures) names a file that exists; every docs page
  // is linked from the README.
  const std::regex link(R"(\]\((docs/[^)#\s]+)(#[^)\s]*)?\))");
  std::vector<std::string> linked;
  for (auto it = std::sregex_iterator(readme.begin(), readme.end(), link); it != std::sregex_iterator(); ++it) {
    const std::string target = (*it)[1];
    CAPTURE(target);
    CHECK(std::filesystem::is_regular_file(kinema_test::sample("../" + target)));
    linked.push_back(target);
  }
  CHECK(std::find(linked.begin(), linked.end(), "docs/limits.md") != linked.end());
  CHECK(std::any_of(linked.begin(), linked.end(), [](const std::string& target) {
    return target.size() > 4 && target.substr(target.size() - 4) == ".png";
  }));
  for (const auto& entry : std::filesystem::directory_iterator(kinema_test::sample("../docs"))) {
    if (entry.path().extension() != ".md") continue;
    const std::string page = "docs/" + entry.path().filename().string();
    CAPTURE(page);
    CHECK(std::find(linked.begin(), linked.end(), page) != linked.end());
  }
}

TEST_CASE("README: links between docs pages lead to files that exist") {
  const std::regex link(R"(\]\(([A-Za-z0-9_./-]+\.(md|png))(#[^)\s]*)?\))");
  for (const auto& entry : std::filesystem::directory_iterator(kinema_test::sample("../docs"))) {
    if (entry.path().extension() != ".md") continue;
    const std::string text = kinema_test::read_file(entry.path().string());
    for (auto it = std::sregex_iterator(text.begin(), text.end(), link); it != std::sregex_iterator(); ++it) {
      const std::string target = (*it)[1];
      CAPTURE(entry.path().filename().string());
      CAPTURE(target);
      CHECK(std::filesystem::is_regular_file(entry.path().parent_path() / target));
    }
  }
}

// Each ```toml snippet of the README follows a mention of the sample it comes from
// (`samples/NAME.toml`), and each of its lines is a line of that sample as it is (but
// a "# ..." line, which says what the snippet leaves out).
TEST_CASE("README's TOML snippets are lines of the samples they name") {
  const std::string readme = project_file("README.md");
  std::size_t snippets = 0;
  for (auto at = readme.find("```toml\n"); at != std::string::npos; at = readme.find("```toml\n", at + 1)) {
    const auto named = readme.rfind("`samples/", at);
    REQUIRE(named != std::string::npos);
    const std::string sample = readme.substr(named + 9, readme.find('`', named + 1) - named - 9);
    CAPTURE(sample);
    const auto sample_lines = lines_of(kinema_test::read_file(kinema_test::sample(sample)));
    REQUIRE(!sample_lines.empty());
    const auto start = at + 8;
    const auto end = readme.find("```", start);
    REQUIRE(end != std::string::npos);
    for (const std::string& line : lines_of(readme.substr(start, end - start))) {
      if (line.empty() || line.rfind("# ...", 0) == 0) continue;  // "# ..." marks what is left out
      CAPTURE(line);
      CHECK(std::find(sample_lines.begin(), sample_lines.end(), line) != sample_lines.end());
    }
    // And the sample loads: the snippet's mechanism is one kinema reads.
    CHECK_NOTHROW(kinema::load_model(kinema_test::sample(sample)));
    ++snippets;
  }
  CHECK(snippets == 3);  // one per form
}

// Issue 33: the docs list every limit with the reason for it. Each kMax constant of the
// sources (engine/, the readers and front ends, cli/) is named in docs/limits.md with its value.
TEST_CASE("docs/limits.md names every kMax constant of the sources with its value") {
  const std::string limits = kinema_test::read_file(kinema_test::sample("../docs/limits.md"));
  REQUIRE(limits.find("| what | limit") != std::string::npos);
  const std::filesystem::path root = std::filesystem::path(kinema_test::sample("..")).lexically_normal();
  const std::regex constant(R"(constexpr[^=;(]*\b(kMax\w+)\s*=\s*([^;]+);)");
  std::map<std::string, double> values;
  for (const char* folder : {"engine", "readers", "loops", "linkages", "chains", "cli", "api", "python"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / folder)) {
      const std::string extension = entry.path().extension().string();
      if (extension != ".cpp" && extension != ".hpp" && extension != ".inc") continue;
      const std::string text = kinema_test::read_file(entry.path().string());
      for (std::sregex_iterator it(text.begin(), text.end(), constant), end; it != end; ++it) {
        std::string expression = (*it)[2];
        expression.erase(std::remove(expression.begin(), expression.end(), '\''), expression.end());
        double value = 1;  // a literal or a product of literals (1024 * 1024)
        std::stringstream factors(expression);
        for (std::string factor; std::getline(factors, factor, '*');) value *= std::stod(factor);
        const std::string name = (*it)[1];
        CAPTURE(name);
        CHECK((values.count(name) == 0 || values[name] == value));  // one name, one value
        values[name] = value;
      }
    }
  }
  CHECK(values.size() >= 20);
  for (const auto& [name, value] : values) {
    CAPTURE(name);
    const auto at = limits.find("`" + name + " = ");
    REQUIRE(at != std::string::npos);
    std::string shown = limits.substr(at + name.size() + 4, 20);
    shown = shown.substr(0, shown.find_first_of("`;"));
    shown.erase(std::remove(shown.begin(), shown.end(), ','), shown.end());
    CAPTURE(shown);
    CHECK(std::stod(shown) == value);
  }
}

TEST_CASE("docs/tutorial.md: every command of the first session runs and writes what it says") {
  // Each line of its ```sh blocks, in order, in a scratch folder: ./build/ is the build's
  // folder, samples/ the project's; a file named by -o (and the PDF) is there afterwards.
  const std::string tutorial = project_file("docs/tutorial.md");
  const std::filesystem::path build = std::filesystem::path(KINEMA_EXE).parent_path();
  const std::filesystem::path samples = kinema_test::sample("");
  const auto folder = kinema_test::scratch_directory() / "tutorial";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::vector<std::string> commands;
  bool in_block = false;
  for (const std::string& line : lines_of(tutorial)) {
    if (line == "```sh") in_block = true;
    else if (line == "```") in_block = false;
    else if (in_block && !line.empty()) commands.push_back(line);
  }
  CHECK(commands.size() >= 7);
  const bool python = std::filesystem::exists(build / "python");
  for (std::string command : commands) {
    CAPTURE(command);
    if (command.find("python3") != std::string::npos && !python) continue;  // built without the module
    command = std::regex_replace(command, std::regex(R"(\./build/)"), build.string() + "/");
    command = std::regex_replace(command, std::regex(R"(build/python)"), (build / "python").string());
    command = std::regex_replace(command, std::regex(R"(samples/)"), samples.string());
    const auto run = kinema_test::run_shell("cd " + kinema_test::shell_quote(folder.string()) + " && " + command);
    CHECK_MESSAGE(run.exit_status == 0, run.err);
    std::smatch output;
    if (std::regex_search(command, output, std::regex(R"(-o (\S+))"))) CHECK(std::filesystem::exists(folder / output[1].str()));
  }
  CHECK(std::filesystem::exists(folder / "four_bar.pdf"));
}
