// The joints-and-links form through the kinema program: `kinema loops` writes the
// vector-loop file kinema found, which evaluates to the same numbers; a structural
// mistake is an input error (status, file:line, no output file).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "test_support.hpp"

TEST_CASE("kinema loops: the vector loops of a joints-and-links sample evaluate to the same numbers") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml"}) {
    CAPTURE(name);
    const std::string directory = kinema_test::fresh_directory("linkage_loops_cli");
    const std::string loops = directory + "/loops.toml";
    const auto written = kinema_test::run_kinema({"loops", kinema_test::sample(name), "-o", loops});
    REQUIRE(written.exit_status == 0);
    CHECK(written.out.empty());
    const std::string text = kinema_test::read_file(loops);
    CHECK(text.find("[loops]") != std::string::npos);
    CHECK(text.find("[joints]") == std::string::npos);
    const auto drawn = kinema_test::run_kinema({"eval", kinema_test::sample(name), "--sweep", "20:160:10", "--format", "csv"});
    const auto by_loops = kinema_test::run_kinema({"eval", loops, "--sweep", "20:160:10", "--format", "csv"});
    REQUIRE(drawn.exit_status == 0);
    REQUIRE(by_loops.exit_status == 0);
    // The same numbers in every column of the loops' output (the drawn file has more:
    // its slider blocks and sliders); the last digits may differ (the drawn file's first
    // row is placed in closed form, the loops' by Newton from the guesses).
    const auto table = [](const std::string& csv) {
      std::vector<std::vector<std::string>> rows(1);
      std::string cell;
      for (char c : csv) {
        if (c == ',' || c == '\n') {
          rows.back().push_back(cell);
          cell.clear();
          if (c == '\n') rows.emplace_back();
        } else {
          cell += c;
        }
      }
      rows.pop_back();
      return rows;
    };
    const auto a = table(drawn.out), b = table(by_loops.out);
    REQUIRE(a.size() == b.size());
    for (std::size_t column = 0; column < b[0].size(); ++column) {
      const auto at = std::find(a[0].begin(), a[0].end(), b[0][column]);
      REQUIRE_MESSAGE(at != a[0].end(), b[0][column]);
      const std::size_t k = static_cast<std::size_t>(at - a[0].begin());
      for (std::size_t row = 1; row < a.size(); ++row) {
        char* end = nullptr;
        const double x = std::strtod(a[row][k].c_str(), &end);
        if (a[row][k].empty() || *end != '\0') {
          CHECK(a[row][k] == b[row][column]);  // status, notes
        } else {
          CHECK(std::fabs(x - std::strtod(b[row][column].c_str(), nullptr)) <= 1e-9 * (1 + std::fabs(x)));
        }
      }
    }
  }
}

TEST_CASE("kinema loops and eval: a joints-and-links file with a mistake writes nothing") {
  const std::string text = kinema_test::read_file(kinema_test::sample("problem_4_4_joints.toml"));
  const std::string bad = kinema_test::write_temporary(
      "linkage_bad.toml", kinema_test::replaced(R"(4 = { joints = ["F", "E"], length = "EF", angle = "phi4" })",
                                                R"(4 = { joints = ["F"], angle = "phi4" })", text));
  for (const char* command : {"loops", "eval", "derive", "latex"}) {
    CAPTURE(command);
    const std::string output = bad + ".out";
    std::filesystem::remove(output);
    const auto result = kinema_test::run_kinema({command, bad, "-o", output});
    CHECK(result.exit_status == 2);  // bad input (cli/exit_status.hpp), not an internal error
    CHECK_FALSE(std::filesystem::exists(output));
    CHECK(result.err.find("linkage_bad.toml:") != std::string::npos);
    CHECK(result.err.find("joint \"E\" is used by link 3 only") != std::string::npos);
  }
}
