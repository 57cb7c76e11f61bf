// Data formats (issue 10). --format npy: a NumPy structured array that numpy.load reads, holding what the CSV
// says, row by row and column by column (issue 10), for every sample, including
// singular and unassembled rows. Read back with Debian's python3-numpy.
#include <doctest/doctest.h>

#include <cctype>
#include <filesystem>
#include <sstream>

#include "engine/base/number_format.hpp"

#include "tests/test_support.hpp"

namespace {

const std::string kChecker = std::string(KINEMA_SAMPLES_DIR) + "/../tests/tools/npy_matches_csv.py";

}  // namespace

TEST_CASE("npy read back with numpy equals the CSV for every sample") {
  const std::string directory = kinema_test::fresh_directory("npy");
  for (const auto& entry : std::filesystem::directory_iterator(KINEMA_SAMPLES_DIR)) {
    if (entry.path().extension() != ".toml") continue;  // a folder of what is read with them (samples/check)
    const std::string path = entry.path().string(), stem = entry.path().stem().string();
    CAPTURE(stem);
    // The piston-driven crank over its whole stroke and past it: singular and unassembled rows.
    const std::string sweep = stem.find("piston") != std::string::npos ? "50:250:1" : "0:360:1";
    const std::string npy = directory + "/" + stem + ".npy", csv = directory + "/" + stem + ".csv";
    REQUIRE(kinema_test::run_kinema({"eval", path, "--sweep", sweep, "--format", "npy", "-o", npy}).exit_status == 0);
    REQUIRE(kinema_test::run_kinema({"eval", path, "--sweep", sweep, "--format", "csv", "-o", csv}).exit_status == 0);
    const auto check = kinema_test::run_shell("/usr/bin/python3 " + kinema_test::shell_quote(kChecker) + " " +
                                              kinema_test::shell_quote(npy) + " " + kinema_test::shell_quote(csv));
    CAPTURE(check.err);
    CHECK(check.exit_status == 0);
    CHECK(check.out.find("columns agree") != std::string::npos);
  }
  // The checker itself fails on a difference (so the check above can fail).
  const std::string four_bar = directory + "/four_bar.csv", other = directory + "/slider_crank.npy";
  CHECK(kinema_test::run_shell("/usr/bin/python3 " + kinema_test::shell_quote(kChecker) + " " +
                               kinema_test::shell_quote(other) + " " + kinema_test::shell_quote(four_bar))
            .exit_status != 0);
}

namespace {

std::vector<std::vector<std::string>> csv_cells(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    rows.emplace_back();
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) rows.back().push_back(cell);
  }
  return rows;
}

// Significant digits of a number as printed ("-3.06e+03" -> 3, "0.00125" -> 3).
int significant_digits(const std::string& text) {
  std::string mantissa = text.substr(0, text.find_first_of("eE"));
  std::string digits;
  for (char c : mantissa)
    if (std::isdigit(static_cast<unsigned char>(c))) digits += c;
  digits.erase(0, digits.find_first_not_of('0'));
  return static_cast<int>(digits.size());
}

}  // namespace

// --precision N: every number of the text formats has at most N significant digits and
// is the default output's value rounded to N (issue 10).
TEST_CASE("--precision sets the significant digits of table, csv and json") {
  const std::string path = kinema_test::sample("problem_4_4_six_bar.toml");
  const auto precise = kinema_test::run_kinema({"eval", path, "--sweep", "0:360:15", "--format", "csv"});
  const auto rounded =
      kinema_test::run_kinema({"eval", path, "--sweep", "0:360:15", "--format", "csv", "--precision", "4"});
  REQUIRE(precise.exit_status == 0);
  REQUIRE(rounded.exit_status == 0);
  const auto a = csv_cells(precise.out), b = csv_cells(rounded.out);
  REQUIRE(a.size() == b.size());
  std::size_t numbers = 0;
  for (std::size_t r = 1; r < a.size(); ++r) {
    REQUIRE(a[r].size() == b[r].size());
    for (std::size_t c = 0; c < a[r].size(); ++c) {
      if (c == 3 || a[r][c].empty()) {
        CHECK(a[r][c] == b[r][c]);  // status, note, empty cells
        continue;
      }
      CAPTURE(b[r][c]);
      CHECK(significant_digits(b[r][c]) <= 4);
      CHECK(std::stod(b[r][c]) == kinema::round_significant(std::stod(a[r][c]), 4));
      ++numbers;
    }
  }
  CHECK(numbers > 500);
  const auto table = kinema_test::run_kinema({"eval", path, "--precision", "3"});
  CHECK(table.out.find("omega2 = -1.13 rad/s") != std::string::npos);  // -1.1307 by default
  const auto json = kinema_test::run_kinema({"eval", path, "--format", "json", "--precision", "3"});
  const auto document = nlohmann::json::parse(json.out);
  CHECK(document["results"][0]["coordinates"]["phi2"]["rate"].get<double>() == -1.13);
  CHECK(kinema_test::run_kinema({"eval", path, "--precision", "0"}).exit_status == 2);
}
