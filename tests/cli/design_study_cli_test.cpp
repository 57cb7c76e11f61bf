// kinema eval --vary (issue 36): each row of a design study equals what a separate
// `kinema eval` of the file edited to that design says (its four-bar figures or its
// slider's time ratio, and its rows' largest rates, speeds and accelerations); the grid
// is every combination; what --vary refuses it names. Run in process.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <string>
#include <vector>

#include "cli/run.hpp"
#include "tests/test_support.hpp"

namespace {

using json = nlohmann::json;

std::filesystem::path scratch() {
  const auto directory = kinema_test::scratch_directory() / "design_study_cli";
  std::filesystem::create_directories(directory);
  return directory;
}

// `kinema eval ARGUMENTS --format json -o FILE` in this process, its output parsed.
json eval_json(std::vector<std::string> arguments) {
  const std::string out = (scratch() / "out.json").string();
  arguments.insert(arguments.begin(), "kinema");
  for (const char* extra : {"-q", "--format", "json", "-o"}) arguments.push_back(extra);
  arguments.push_back(out);
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  REQUIRE(kinema_cli::run(static_cast<int>(argv.size()), argv.data()) == 0);
  return json::parse(kinema_test::read_file(out));
}

// Both null (undefined), or equal to `tolerance` relative.
void check_same(const json& study, double separate, const std::string& what, double tolerance) {
  INFO(what << ": study " << study.dump() << ", separate run " << separate);
  if (std::isnan(separate)) {
    CHECK(study.is_null());
  } else {
    REQUIRE(study.is_number());
    CHECK(std::fabs(study.get<double>() - separate) <= tolerance * std::max(1.0, std::fabs(separate)));
  }
}

// The largest |x| of a separate run's rows whose status is ok.
double largest(const json& run, const std::function<double(const json&)>& value) {
  double most = NAN;
  for (const json& row : run["results"])
    if (row["status"] == "ok" && !(std::fabs(value(row)) <= most)) most = std::fabs(value(row));
  return most;
}

// One study row against the separate run of the sample edited to its design.
void check_row(const json& design, const json& run) {
  // 1e-12, but a change-point design passes a singular position once a turn, where the
  // study's lanes (another order of operations, fused multiply-adds) and the scalar solver
  // agree only to Newton's tolerance over the least singular value (as the engine's test
  // says; 1.2e-12 seen in the Debug build): there 1e-10.
  const double tolerance =
      run.contains("four_bar") && run["four_bar"]["grashof"] == "change point" ? 1e-10 : 1e-12;
  std::size_t failed = 0;
  for (const json& row : run["results"]) failed += row["status"] == "unassembled";
  CHECK(design["failed_values"] == failed);
  CHECK(design["assembles"] == (failed == 0));
  if (run.contains("four_bar")) {
    CHECK(design["grashof"] == run["four_bar"]["grashof"]);
    check_same(design["min_transmission_angle"], run["four_bar"]["transmission_angle"]["least"].get<double>(),
               "least transmission angle", tolerance);
  } else {
    CHECK(design["grashof"] == "n/a");
  }
  if (run.contains("strokes")) check_same(design["time_ratio"], run["strokes"][0]["time_ratio"].get<double>(), "time ratio", tolerance);
  for (const json& c : run["coordinates"]) {
    const std::string name = c["name"];
    check_same(design["max_abs_" + c["rate_name"].get<std::string>()],
               largest(run, [&](const json& row) { return row["coordinates"][name]["rate"].get<double>(); }), name, tolerance);
    check_same(design["max_abs_" + c["second_rate_name"].get<std::string>()],
               largest(run, [&](const json& row) { return row["coordinates"][name]["second_rate"].get<double>(); }), name, tolerance);
  }
  for (const json& p : run["points"]) {
    const std::string name = p;
    check_same(design["max_" + name + "_speed"],
               largest(run, [&](const json& row) { return row["points"][name]["speed"].get<double>(); }), name, tolerance);
    check_same(design["max_" + name + "_acceleration"],
               largest(run, [&](const json& row) { return row["points"][name]["acceleration_magnitude"].get<double>(); }),
               name, tolerance);
  }
}

// The study of `sample` over a grid of two parameters (written `name = "V unit"` in the
// file) against separate runs of the file edited to each design.
void check_study_rows(const std::string& sample, const std::string& unit, const std::string& first, const std::string& first_written,
                      const std::vector<std::string>& first_values, const std::string& second, const std::string& second_written,
                      const std::vector<std::string>& second_values, const std::string& sweep) {
  const std::string range = [&] {
    return first + "=" + first_values.front() + ":" + first_values.back() + ":" +
           std::to_string(std::stod(first_values[1]) - std::stod(first_values[0]));
  }();
  const json study = eval_json({"eval", kinema_test::sample(sample), "--vary", range, "--vary",
                                second + "=" + second_values.front() + " " + unit + ":" + second_values.back() + " " +
                                    unit + ":" + std::to_string(std::stod(second_values[1]) - std::stod(second_values[0])) + " " + unit,
                                "--sweep", sweep});
  REQUIRE(study["designs"].size() == first_values.size() * second_values.size());
  std::size_t i = 0;
  for (const std::string& x : first_values) {
    for (const std::string& y : second_values) {
      const json& design = study["designs"][i++];
      INFO(first << " = " << x << ", " << second << " = " << y);
      CHECK(design[first].get<double>() == doctest::Approx(std::stod(x)).epsilon(1e-12));
      CHECK(design[second].get<double>() == doctest::Approx(std::stod(y)).epsilon(1e-12));
      std::string text = kinema_test::read_file(kinema_test::sample(sample));
      text = kinema_test::replaced(first + " = \"" + first_written + "\"", first + " = \"" + x + " " + unit + "\"", text);
      text = kinema_test::replaced(second + " = \"" + second_written + "\"", second + " = \"" + y + " " + unit + "\"", text);
      const std::string edited = (scratch() / sample).string();
      std::ofstream(edited) << text;
      check_row(design, eval_json({"eval", edited, "--sweep", sweep}));
    }
  }
}

}  // namespace

TEST_CASE("kinema eval --vary: a four-bar's rows equal separate runs of the file edited to each design") {
  // 130/70 is a change point (folded flat once a turn); the sweep is the turn the
  // separate run's figures take, from the file's 40 deg.
  check_study_rows("four_bar.toml", "mm", "b", "120 mm", {"110", "120", "130"}, "c", "80 mm", {"70", "80"}, "40:400:1");
}

TEST_CASE("kinema eval --vary: a slider-crank's rows, time ratio included, equal separate runs") {
  check_study_rows("slider_crank.toml", "mm", "a", "50 mm", {"40", "60"}, "e", "10 mm", {"0", "10", "20"}, "0:360:1");
}

TEST_CASE("kinema eval --vary: names what it refuses") {
  const auto refused = [](std::vector<std::string> arguments) {
    const kinema_test::CommandResult r = kinema_test::run_kinema(arguments);
    CHECK(r.exit_status != 0);
    return r.err;
  };
  const std::string file = kinema_test::sample("four_bar.toml");
  CHECK(refused({"eval", file, "--vary", "bb=1:2:1", "--sweep", "0:360:1", "--format", "csv"})
            .find("no parameter named \"bb\" (there are: a, b, c, d, p, delta)") != std::string::npos);
  CHECK(refused({"eval", file, "--vary", "b=130:110:1", "--sweep", "0:360:1", "--format", "csv"})
            .find("the range of b \"130:110:1\" never reaches its stop") != std::string::npos);
  CHECK(refused({"eval", file, "--vary", "b=1 deg:2 deg:1 deg", "--sweep", "0:360:1", "--format", "csv"})
            .find("parameter \"b\" is a length, but \"1 deg\"") != std::string::npos);
  CHECK(refused({"eval", file, "--vary", "b=110:130:1", "--sweep", "0:360:1"}).find("as csv, json or npy") != std::string::npos);
  // A joints file's length that kinema took from its sketch: refused as that.
  CHECK(refused({"eval", kinema_test::sample("triple_rocker_circuit.toml"), "--vary", "x_D=1:2:1", "--format", "csv"})
            .find("no parameter named \"x_D\" that the file writes: kinema made it") != std::string::npos);
}
