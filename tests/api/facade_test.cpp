// The library facade (<kinema/kinema.hpp>): what it reads by name is what the engine
// computes at that index, input values with units are the SI ones, a name the
// mechanism does not have is refused with what it has, and a value that does not
// assemble is a status with kinema's sentence, not NaN. Its header stays small: no
// GiNaC, Eigen or engine header behind it.
#include <doctest/doctest.h>

#include <kinema/kinema.hpp>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "engine/model.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "readers/mechanism_file.hpp"

#include "tests/test_support.hpp"

using kinema_test::sample;

namespace {

// Every name of the facade's solutions read against the engine's table at that index,
// for the same input values (SI).
void check_named_equals_indexed(const std::string& sample_name, const std::vector<double>& inputs) {
  INFO(sample_name);
  const kinema::MechanismModel facade(sample(sample_name));
  const kinema::Model model = kinema::load_model(sample(sample_name));
  const kinema::MotionTable table = kinema::solve_motion(model, inputs);
  const std::vector<kinema::Solution> solutions = facade.solve(inputs);
  const kinema::Names& names = facade.names();
  REQUIRE(solutions.size() == inputs.size());
  REQUIRE(names.unknowns.size() == model.system.unknowns.size());
  REQUIRE(names.points.size() == model.system.points.size());
  REQUIRE(names.frames.size() == model.system.frames.size());
  CHECK(names.input == model.system.input.name);
  for (std::size_t row = 0; row < inputs.size(); ++row) {
    const kinema::Solution& s = solutions[row];
    REQUIRE(table.status(row) == kinema::Status::ok);
    REQUIRE(s.ok());
    CHECK(s.input() == table.input(row));
    CHECK(s.value(names.input) == table.input(row));
    CHECK(s.rate(names.input_rate) == table.input_rate(row));
    CHECK(s.second_rate(names.input_second_rate) == table.input_second_rate(row));
    for (std::size_t i = 0; i < names.unknowns.size(); ++i) {
      INFO(names.unknowns[i]);
      CHECK(names.unknowns[i] == model.system.unknowns[i].name);
      CHECK(s.value(names.unknowns[i]) == table.q(row)[Eigen::Index(i)]);
      CHECK(s.rate(names.rates[i]) == table.qd(row)[Eigen::Index(i)]);
      CHECK(s.second_rate(names.second_rates[i]) == table.qdd(row)[Eigen::Index(i)]);
    }
    for (std::size_t p = 0; p < names.points.size(); ++p) {
      INFO(names.points[p]);
      const kinema::PointMotion engine = table.point(row, p);
      const kinema::PointResult& named = s.point(names.points[p]);
      CHECK(named.dimension == engine.dimension);
      CHECK(named.position == engine.position);
      CHECK(named.velocity == engine.velocity);
      CHECK(named.acceleration == engine.acceleration);
    }
    for (std::size_t f = 0; f < names.frames.size(); ++f) {
      INFO(names.frames[f]);
      CHECK(s.frame(names.frames[f]).angular_velocity == table.frame(row, f).angular_velocity);
      CHECK(s.frame(names.frames[f]).angular_acceleration == table.frame(row, f).angular_acceleration);
    }
  }
}

// The message of the kinema::Error that `read` throws ("" when it throws none).
template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const kinema::Error& error) {
    return error.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("facade: names read the engine's values at their index (vector loops, joints and links, a spatial chain)") {
  const std::vector<double> angles = {kinema::degrees(10), kinema::degrees(35), kinema::degrees(60)};
  check_named_equals_indexed("four_bar.toml", angles);
  check_named_equals_indexed("problem_3_22_joints.toml", angles);
  check_named_equals_indexed("rssr_spatial_four_bar.toml", angles);
  check_named_equals_indexed("piston_driven_crank.toml", {0.17, 0.16});  // a slider's input, m
}

TEST_CASE("facade: a braced list of values is a list, in SI or with units") {
  const kinema::MechanismModel four_bar(sample("four_bar.toml"));
  const std::vector<kinema::Solution> with_units = four_bar.solve({"10 deg", "20 deg"});
  const std::vector<kinema::Solution> in_si = four_bar.solve({kinema::degrees(10), kinema::degrees(20)});
  REQUIRE(with_units.size() == 2);
  REQUIRE(in_si.size() == 2);
  CHECK(with_units[1].rate("omega3") == in_si[1].rate("omega3"));
  CHECK(with_units[1].input() == doctest::Approx(kinema::degrees(20)));
}

TEST_CASE("facade: the rate names are the file's (omega3 of theta3, a driver's rate_name)") {
  const kinema::MechanismModel four_bar(sample("four_bar.toml"));
  CHECK(four_bar.names().rates == std::vector<std::string>{"omega3", "omega4"});
  CHECK(four_bar.names().second_rates == std::vector<std::string>{"alpha3", "alpha4"});
  CHECK(four_bar.names().input_unit == "rad");
  const kinema::MechanismModel joints(sample("example_4_1_joints.toml"));
  CHECK(joints.names().input_rate == "omega1");  // rate_name = "omega1" under [driver]
  CHECK(kinema::MechanismModel(sample("piston_driven_crank.toml")).names().input_unit == "m");
}

TEST_CASE("facade: input values with units are their SI values") {
  const kinema::MechanismModel four_bar(sample("four_bar.toml"));
  const kinema::Solution in_degrees = four_bar.solve("30 deg");
  CHECK(in_degrees.input() == doctest::Approx(0.5235987755982988).epsilon(1e-15));
  CHECK(four_bar.solve(kinema::degrees(30)).rate("omega3") == in_degrees.rate("omega3"));
  CHECK(four_bar.solve("0.5235987755982988 rad").rate("omega3") == doctest::Approx(in_degrees.rate("omega3")));
  // A bare number is read as kinema eval --at reads it: degrees for an angle input.
  CHECK(four_bar.solve("30").input() == in_degrees.input());
  // A slider's input: millimetres, or the file's length unit when bare (mm here).
  const kinema::MechanismModel piston(sample("piston_driven_crank.toml"));
  CHECK(piston.solve("160 mm").input() == doctest::Approx(0.16).epsilon(1e-15));
  CHECK(piston.solve(kinema::millimetres(160)).value("theta3") == piston.solve("160 mm").value("theta3"));
  // A unit of another kind than the input's is refused, naming both.
  const std::string wrong_kind = error_of([&] { four_bar.solve("30 mm"); });
  CHECK(contains(wrong_kind, "\"30 mm\" is a length, but theta2 is an angle"));
  CHECK(contains(error_of([&] { four_bar.solve("30 furlongs"); }), "furlongs"));
}

TEST_CASE("facade: a name the mechanism does not have is refused, naming what it has") {
  const kinema::MechanismModel four_bar(sample("four_bar.toml"));
  const kinema::Solution s = four_bar.solve("30 deg");
  const std::string no_rate = error_of([&] { s.rate("omega9"); });
  CHECK(contains(no_rate, "four_bar.toml: no rate named \"omega9\" (there are: omega3, omega4)"));
  // A coordinate's name is not a rate's, nor the other way round.
  CHECK(contains(error_of([&] { s.rate("theta3"); }), "no rate named \"theta3\""));
  CHECK(contains(error_of([&] { s.value("omega3"); }), "no coordinate named \"omega3\" (there are: theta3, theta4)"));
  CHECK(contains(error_of([&] { s.point("Q"); }), "no point named \"Q\" (there are: A, B, P)"));
  CHECK(contains(error_of([&] { s.frame("E2"); }), "no frame named \"E2\" (there are: none)"));
  // A bad file is an Error with file:line, as the command line says it.
  const std::string bad = error_of([] { kinema::MechanismModel::from_toml("title = 3\n", "bad.toml"); });
  CHECK(contains(bad, "bad.toml"));
}

TEST_CASE("facade: a value that does not assemble is a status and kinema's sentence, not NaN") {
  // The ground link longer than the other three together: ABCD never closes.
  const std::string text = kinema_test::replaced("d = \"100 mm\"", "d = \"400 mm\"");
  const kinema::MechanismModel never_closes = kinema::MechanismModel::from_toml(text, "long_ground.toml");
  const kinema::Solution s = never_closes.solve("30 deg");
  CHECK(s.status() == kinema::SolutionStatus::unassembled);
  CHECK_FALSE(s.ok());
  CHECK(s.values().empty());
  CHECK(s.rates().empty());
  CHECK(s.points().empty());
  // The sentence is the engine's, as kinema eval prints it.
  const kinema::Model model = kinema::make_model(kinema::read_mechanism_text(text, "long_ground.toml"));
  const kinema::MotionTable table = kinema::solve_motion(model, {kinema::degrees(30)});
  CHECK(s.message() == "long_ground.toml: " + kinema::describe_failure(model.system, table[0]));
  CHECK(contains(s.message(), "ABCD"));
  // Asking it for a value throws that sentence.
  CHECK(contains(error_of([&] { s.value("theta3"); }), s.message()));
  CHECK(contains(error_of([&] { s.point("P"); }), s.message()));
  // A list keeps going past a value that does not assemble (joints and links: at 0 deg
  // the triple rocker's dyad does not reach, at 90 deg it does).
  const kinema::MechanismModel rocker(sample("triple_rocker_circuit.toml"));
  const std::vector<kinema::Solution> list = rocker.solve({"0 deg", "90 deg"});
  CHECK(list[0].status() == kinema::SolutionStatus::unassembled);
  CHECK(contains(list[0].message(), "cannot close at phi = 0 deg"));
  CHECK(list[1].ok());
  CHECK(list[1].message().empty());
}

TEST_CASE("facade: <kinema/kinema.hpp> preprocesses to at most 60,000 lines and includes no GiNaC, Eigen or engine header") {
  // The compiler that builds kinema, preprocessing a file that includes the facade alone
  // with the facade's folders as its only kinema include paths (as an installed program:
  // api/kinema/ and <kinema/error.hpp>, the build's copy of the base's error).
  const std::string source = kinema_test::write_temporary("facade_only.cpp", "#include <kinema/kinema.hpp>\n");
  const std::string preprocessed = kinema_test::write_temporary("facade_only.ii", "");
  const auto result = kinema_test::run_shell(std::string(KINEMA_CXX) + " -std=c++17 -E -I " +
                                             kinema_test::shell_quote(KINEMA_FACADE_INCLUDE_DIR) + " -I " +
                                             kinema_test::shell_quote(KINEMA_FACADE_ERROR_DIR) + " " +
                                             kinema_test::shell_quote(source) + " -o " +
                                             kinema_test::shell_quote(preprocessed));
  REQUIRE_MESSAGE(result.exit_status == 0, result.err);
  const std::string text = kinema_test::read_file(preprocessed);
  std::size_t lines = 0;
  std::istringstream in(text);
  std::vector<std::string> headers;  // the line markers: # 1 "/usr/include/c++/12/string" ...
  for (std::string line; std::getline(in, line); ++lines) {
    if (line.rfind("# ", 0) == 0 && line.find('"') != std::string::npos) headers.push_back(line);
  }
  MESSAGE("g++ -E of #include <kinema/kinema.hpp>: " << lines << " lines");
  CHECK(lines > 1000);  // the standard headers it needs are there: the count counts them
  CHECK(lines <= 60000);
  std::string not_the_facades;  // a header of GiNaC, CLN, Eigen or kinema's engine
  for (const std::string& marker : headers) {
    for (const char* part : {"ginac", "cln/", "eigen3", "Eigen/", "/engine/", "/readers/", "/loops/", "/linkages/", "/chains/"}) {
      if (contains(marker, part)) not_the_facades += marker + "\n";
    }
  }
  CHECK(contains(text, "kinema/kinema.hpp"));  // the markers do name headers
  CHECK(not_the_facades == "");
}

TEST_CASE("facade: sensitivity equals central differences of with_parameters, in SI") {
  const kinema::MechanismModel four_bar(sample("four_bar.toml"));
  const std::vector<double> values{kinema::degrees(40), kinema::degrees(100), kinema::degrees(250)};  // none where it is 0
  const std::vector<double> exact = four_bar.sensitivity("omega3", "b", values);
  REQUIRE(exact.size() == values.size());
  // b = 120 mm moved by 1e-5 of itself: differences exact to ~1e-9 of the derivative.
  const double h = 1.2e-6;
  const std::vector<kinema::Solution> above = four_bar.with_parameters({{"b", "0.1200012 m"}}).solve(values),
                                      below = four_bar.with_parameters({{"b", "0.1199988 m"}}).solve(values);
  for (std::size_t r = 0; r < values.size(); ++r) {
    const double difference = (above[r].rate("omega3") - below[r].rate("omega3")) / (2 * h);
    INFO("row " << r << ": exact " << exact[r] << " (rad/s per m), differences " << difference);
    CHECK(std::fabs(exact[r] - difference) <= 1e-6 * std::fabs(exact[r]));
  }
  CHECK_THROWS_WITH_AS(four_bar.sensitivity("omega3", "bb", values), doctest::Contains("(there are: a, b, c, d, p, delta)"),
                       kinema::Error);
}
