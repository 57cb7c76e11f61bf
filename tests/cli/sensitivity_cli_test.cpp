// kinema eval --sensitivity: the derivative columns d_<column>_d_<parameter> in every
// format (table, csv, json, npy), with the column's unit per the parameter's, holding the
// engine's exact derivatives (engine/analysis/sensitivities, tested against finite
// differences in tests/engine/numeric/sensitivity_test.cpp); and the errors naming what
// the file has.
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "engine/analysis/sensitivities.hpp"
#include "engine/base/units.hpp"
#include "engine/model.hpp"
#include "tests/test_support.hpp"

namespace {

const std::string kChecker = std::string(KINEMA_SAMPLES_DIR) + "/../tests/tools/npy_matches_csv.py";

std::vector<std::string> split(const std::string& line, char separator) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, separator);) cells.push_back(cell);
  if (!line.empty() && line.back() == separator) cells.emplace_back();  // an empty last cell
  return cells;
}

// The engine's values of the columns asked for at the four-bar's inputs (output units).
std::vector<double> engine_values(const std::vector<std::string>& asked, const std::vector<double>& inputs) {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"), kinema::DerivationScope::evaluation);
  const kinema::Sensitivities sensitivities(model, kinema::sensitivity_columns(model.system, asked));
  const kinema::MotionTable table = kinema::solve_motion(model, inputs);
  std::vector<double> values(sensitivities.columns().size() * inputs.size());
  sensitivities.rows(table, 0, table.size(), values.data());
  return values;
}

}  // namespace

TEST_CASE("cli/eval --sensitivity: csv columns named d_COLUMN_d_PARAMETER in the column's unit per the parameter's") {
  const auto run = kinema_test::run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--angle", "40", "--format",
                                            "csv", "--sensitivity", "omega3:b", "--sensitivity", "P_x:delta"});
  REQUIRE(run.exit_status == 0);
  const std::vector<std::string> lines = split(run.out.substr(0, run.out.find_last_not_of('\n') + 1), '\n');
  REQUIRE(lines.size() == 2);
  const std::vector<std::string> header = split(lines[0], ','), row = split(lines[1], ',');
  REQUIRE(header.size() >= 3);
  CHECK(header[header.size() - 3] == "d_omega3_d_b [rad/s/mm]");
  CHECK(header[header.size() - 2] == "d_P_x_d_delta [mm/deg]");
  CHECK(header.back() == "note");
  const std::vector<double> expected = engine_values({"omega3:b", "P_x:delta"}, {kinema::from_degrees(40)});
  REQUIRE(row.size() == header.size());
  // csv prints 12 significant digits.
  CHECK(std::stod(row[row.size() - 3]) == doctest::Approx(expected[0]).epsilon(1e-11));
  CHECK(std::stod(row[row.size() - 2]) == doctest::Approx(expected[1]).epsilon(1e-11));
  CHECK(expected[0] != 0.0);
}

TEST_CASE("cli/eval --sensitivity: json rows carry every derivative of a parameter, named in the head") {
  const std::vector<std::string> names = kinema::differentiable_columns(
      kinema::load_model(kinema_test::sample("four_bar.toml"), kinema::DerivationScope::evaluation).system);
  const nlohmann::json doc = kinema_test::eval_json("four_bar.toml", {"--sweep", "0:90:45", "--sensitivity", "b"});
  REQUIRE(doc["sensitivities"].size() == names.size());
  CHECK(doc["sensitivities"][0]["name"] == "d_" + names[0] + "_d_b");
  CHECK(doc["sensitivities"][0]["unit"] == "deg/mm");  // theta3 in deg, b in mm
  const std::vector<double> expected =
      engine_values({"b"}, {0.0, kinema::from_degrees(45), kinema::from_degrees(90)});
  REQUIRE(doc["results"].size() == 3);
  for (std::size_t r = 0; r < 3; ++r) {
    const nlohmann::json& row = doc["results"][r]["sensitivities"];
    REQUIRE(row.size() == names.size());
    for (std::size_t k = 0; k < names.size(); ++k) {
      INFO(names[k] << " row " << r);
      CHECK(row["d_" + names[k] + "_d_b"].get<double>() == doctest::Approx(expected[r * names.size() + k]).epsilon(1e-9));
    }
  }
}

TEST_CASE("cli/eval --sensitivity: npy fields are the csv's columns, value for value; the table lists them") {
  const std::string directory = kinema_test::fresh_directory("sensitivity_npy");
  const std::string npy = directory + "/four_bar.npy", csv = directory + "/four_bar.csv";
  const std::vector<std::string> run{"eval", kinema_test::sample("four_bar.toml"), "--sweep", "0:360:30", "--sensitivity",
                                     "c", "--sensitivity", "alpha3:delta", "--format"};
  auto with = [&](const std::string& format, const std::string& out) {
    std::vector<std::string> arguments = run;
    arguments.insert(arguments.end(), {format, "-o", out});
    return kinema_test::run_kinema(arguments).exit_status;
  };
  REQUIRE(with("npy", npy) == 0);
  REQUIRE(with("csv", csv) == 0);
  CHECK(kinema_test::read_file(csv).find("d_alpha3_d_delta [rad/s^2/deg]") != std::string::npos);
  const auto check = kinema_test::run_shell("/usr/bin/python3 " + kinema_test::shell_quote(kChecker) + " " +
                                            kinema_test::shell_quote(npy) + " " + kinema_test::shell_quote(csv));
  CAPTURE(check.err);
  CHECK(check.exit_status == 0);
  CHECK(check.out.find("columns agree") != std::string::npos);
  CHECK(kinema_test::read_file(npy).find("'d_alpha3_d_delta'") != std::string::npos);

  const auto table = kinema_test::run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--angle", "40",
                                              "--sensitivity", "omega3:b"});
  REQUIRE(table.exit_status == 0);
  const std::size_t at = table.out.find("d_omega3_d_b");
  REQUIRE(at != std::string::npos);
  const std::string line = table.out.substr(at, table.out.find('\n', at) - at);
  const std::vector<double> expected = engine_values({"omega3:b"}, {kinema::from_degrees(40)});
  CHECK(line.find(" rad/s/mm") != std::string::npos);
  CHECK(std::stod(line.substr(line.find_first_not_of(' ', std::string("d_omega3_d_b").size()))) ==
        doctest::Approx(expected[0]).epsilon(1e-5));  // 6 significant digits
}

TEST_CASE("cli/eval --sensitivity: an unknown parameter or column is named with the file's names") {
  const auto parameter = kinema_test::run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--angle", "40",
                                                  "--sensitivity", "omega3:bb"});
  CHECK(parameter.exit_status == 2);
  CHECK(parameter.out.empty());
  CHECK(parameter.err.find("no parameter named \"bb\" (there are: a, b, c, d, p, delta)") != std::string::npos);
  const auto column = kinema_test::run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--angle", "40",
                                               "--sensitivity", "omega9:b"});
  CHECK(column.exit_status == 2);
  CHECK(column.err.find("no output column named \"omega9\" that has a derivative (there are: theta3, omega3, alpha3") !=
        std::string::npos);
}
