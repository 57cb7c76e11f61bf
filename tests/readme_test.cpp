// The README says what is true: its library example is examples/library_usage.cpp
// as it is (that file is built against an installed kinema and run by the
// "package: ..." test), the folders its "How it works" names exist, and its first
// example output is the program's.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include "test_support.hpp"

TEST_CASE("README shows examples/library_usage.cpp verbatim, and the folders it names exist") {
  const std::string readme = kinema_test::read_file(kinema_test::sample("../README.md"));
  const std::string example = kinema_test::read_file(kinema_test::sample("../examples/library_usage.cpp"));
  REQUIRE(!readme.empty());
  REQUIRE(example.find("kinema::analyse(model") != std::string::npos);
  CHECK(readme.find("```cpp\n" + example + "```") != std::string::npos);
  for (const char* folder : {"loops", "engine/symbolic", "engine/numeric", "engine/report", "engine/printers/text",
                             "engine/printers/data", "engine/printers/latex", "engine/printers/code", "cli"}) {
    CAPTURE(folder);
    CHECK(std::filesystem::is_directory(kinema_test::sample(std::string("../") + folder)));
  }
}

TEST_CASE("README's \"What it prints\" is what the command prints") {
  const std::string readme = kinema_test::read_file(kinema_test::sample("../README.md"));
  const auto result = kinema_test::run_kinema({"eval", kinema_test::sample("problem_4_4_six_bar.toml")});
  REQUIRE(result.exit_status == 0);
  CHECK(readme.find("```\n$ ./build/kinema eval samples/problem_4_4_six_bar.toml\n" + result.out + "```") !=
        std::string::npos);
}

// Issue 33: the docs list every limit with the reason for it. Each kMax constant of the
// sources (engine/, loops/, cli/) is named in README's "Limits" table with its value.
TEST_CASE("README's Limits table names every kMax constant of the sources with its value") {
  const std::string readme = kinema_test::read_file(kinema_test::sample("../README.md"));
  const auto section = readme.find("### Limits");
  REQUIRE(section != std::string::npos);
  const std::string limits = readme.substr(section, readme.find("\n## ", section) - section);
  const std::filesystem::path root = std::filesystem::path(kinema_test::sample("..")).lexically_normal();
  const std::regex constant(R"(constexpr[^=;(]*\b(kMax\w+)\s*=\s*([^;]+);)");
  std::map<std::string, double> values;
  for (const char* folder : {"engine", "loops", "cli"}) {
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
