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

#include "readers/mechanism_file.hpp"

#include "tests/test_support.hpp"

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

TEST_CASE("kinema eval --circuit: one closed motion through the toggles, in every format, each row with its branch") {
  const std::string sample = kinema_test::sample("triple_rocker_circuit.toml");
  const auto csv = kinema_test::run_kinema({"eval", sample, "--circuit", "1", "--format", "csv"});
  REQUIRE(csv.exit_status == 0);
  CHECK(csv.err.empty());
  std::vector<std::string> lines;
  for (std::size_t at = 0, end; (end = csv.out.find('\n', at)) != std::string::npos; at = end + 1)
    lines.push_back(csv.out.substr(at, end - at));
  REQUIRE(lines.size() == 1 + 625);
  CHECK(lines[0].find(",branch_C [sign],note") != std::string::npos);
  CHECK(lines[1].rfind("90,10,0,ok,", 0) == 0);
  CHECK(lines.back().rfind("90,10,0,ok,", 0) == 0);
  int singular = 0;
  for (const std::string& line : lines) singular += line.find(",singular,") != std::string::npos;
  CHECK(singular == 2);

  const nlohmann::json doc = kinema_test::eval_json("triple_rocker_circuit.toml", {"--circuit", "1"});
  const nlohmann::json& rows = doc["results"];
  REQUIRE(rows.size() == 625);
  int reversals = 0, changes = 0;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    reversals += rows[r]["input_rate"].get<double>() != rows[r - 1]["input_rate"].get<double>();
    changes += rows[r]["branch"]["C"].get<int>() != rows[r - 1]["branch"]["C"].get<int>();
    if (rows[r]["status"] == "singular") {
      CHECK(rows[r]["message"].get<std::string>().find("dyad 1 (RRR: links 2, 3; joints B, C, D) is at a toggle at phi = ") == 0);
    }
  }
  CHECK(reversals == 2);
  CHECK(changes == 2);

  const auto table = kinema_test::run_kinema({"eval", sample, "--circuit", "1 deg"});
  REQUIRE(table.exit_status == 0);
  CHECK(table.out.find("  branch: C -1 (each dyad's assembly sign, by its inner joint)\n") != std::string::npos);
  const auto npy = kinema_test::run_kinema({"eval", sample, "--circuit", "1", "--format", "npy"});
  REQUIRE(npy.exit_status == 0);
  CHECK(npy.out.find("('branch_C', '<f8')") != std::string::npos);
}

TEST_CASE("kinema eval --circuit: what it cannot follow is said, with a usage or input status and no output") {
  const std::string directory = kinema_test::fresh_directory("circuit_errors");
  const std::string output = directory + "/out.csv";
  const std::string rocker = kinema_test::sample("triple_rocker_circuit.toml");
  struct Case {
    std::vector<std::string> arguments;
    int status;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"eval", kinema_test::sample("four_bar.toml"), "--circuit", "1"}, 2, "four_bar.toml: --circuit follows a mechanism described by joints and links"},
      {{"eval", rocker, "--circuit", "0"}, 2, "--circuit 0: the step must be a positive number"},
      {{"eval", rocker, "--circuit", "x"}, 2, "--circuit x: "},
      {{"eval", rocker, "--circuit", "1", "--sweep", "0:10:1"}, 2, "--sweep excludes --circuit"},
      {{"eval", rocker, "--circuit", "1", "--angle", "100", "--angle", "120"}, 2, "--circuit starts at one value"},
      {{"eval", rocker, "--circuit", "1", "--angle", "0"}, 3,
       "triple_rocker_circuit.toml: the circuit cannot start at phi = 0 deg: dyad 1 (RRR: links 2, 3; joints B, C, D) "
       "cannot close there"},
      {{"eval", rocker, "--circuit", "0.0001"}, 2,
       "--circuit 0.0001: a turn of the input is 3600000 rows, more than the 500000 rows a circuit of 2 unknowns may "
       "have"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> arguments = c.arguments;
    arguments.insert(arguments.end(), {"-o", output});
    CAPTURE(c.message);
    const auto result = kinema_test::run_kinema(arguments);
    CHECK(result.exit_status == c.status);
    CHECK(result.err.find(c.message) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(output));
  }
}

// Audit 2026-11-24 (tests/fuzz/regressions/loops_multiline_description.toml): a line break in
// the title or description was written into a TOML string as it was, and kinema could not
// read the file it had written. Written back, a file reads as the same mechanism, and
// `kinema loops` of its own output gives the same bytes.
TEST_CASE("kinema loops: line breaks, quotes, backslashes, tabs and Unicode in the text round-trip") {
  const std::string directory = kinema_test::fresh_directory("loops_round_trip");
  std::string text = kinema_test::replaced(
      "title = \"four-bar\"", "title = \"four-bar \\\"open\\\" C:\\\\notes\\tθ\\nsecond line\"\n"
                              "description = \"\"\"\nA crank-rocker.\n\n  Open branch \\\\ \"quoted\".\"\"\"");
  text = kinema_test::replaced("theta3 = \"20 deg\"", "theta3 = { guess = \"20 deg\", latex = '\\hat{\\varphi}_{3}' }", text);
  for (const std::string& file :
       {kinema_test::write_temporary("round_trip.toml", text),
        kinema_test::sample("../tests/fuzz/regressions/loops_multiline_description.toml")}) {
    CAPTURE(file);
    const std::string once = directory + "/once.toml", twice = directory + "/twice.toml";
    REQUIRE(kinema_test::run_kinema({"loops", file, "-o", once}).exit_status == 0);
    const auto again = kinema_test::run_kinema({"loops", once, "-o", twice});
    INFO(again.err);
    REQUIRE(again.exit_status == 0);
    CHECK(kinema_test::read_file(twice) == kinema_test::read_file(once));
    const kinema::Mechanism original = kinema::read_mechanism_file(file), written = kinema::read_mechanism_file(once);
    CHECK(written.title == original.title);
    CHECK(written.description == original.description);
    CHECK(written.unknowns[0].latex_name == original.unknowns[0].latex_name);
    const auto a = kinema_test::run_kinema({"eval", file, "--format", "json"});
    const auto b = kinema_test::run_kinema({"eval", once, "--format", "json"});
    REQUIRE(a.exit_status == 0);
    CHECK(b.out == a.out);  // the same title and numbers
  }
  CHECK(kinema::read_mechanism_text(text, "t.toml").title == "four-bar \"open\" C:\\notes\tθ\nsecond line");
}
