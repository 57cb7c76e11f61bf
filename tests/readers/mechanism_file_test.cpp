// readers/mechanism_file: the TOML reader, through the library. Quantities come
// out in SI, entries in the order written (TOML tables are unordered), every
// error names file:line, sweeps are expanded into SI values.
#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/model.hpp"
#include "readers/answers_file.hpp"
#include "readers/class_table.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

using kinema::Dimension;
using kinema::Mechanism;
using kinema::read_mechanism_text;
using kinema_test::four_bar_text;
using kinema_test::replaced;

namespace {

constexpr double kDeg = M_PI / 180.0;

// Every section, names out of alphabetical order, every way of writing a value.
// The line numbers matter (checked below).
const char* const kFullText = R"toml(title = "reader test"
description = "all sections"
[parameters]
zeta = "2 in"
a = "40 mm"
m = "a/2"
k = 3
g = 0.1
delta = "30 deg"
[input]
name = "theta2"
values = ["30 deg", "0.5 rad"]
rate = "60 rpm"
second_rate = "2 rad/s^2"
rate_name = "w2"
second_rate_name = "al2"
[unknowns]
theta4 = "80 deg"
theta3 = "20 deg"
s = { guess = "5 cm", rate_name = "sd", second_rate_name = "sdd", latex = '\varsigma' }
[loops]
Zloop = "a*exp(I*theta2) + s*exp(I*theta3) - zeta*exp(I*theta4) - m"
Aloop = { x = "a*cos(theta3) - s", y = "zeta*sin(theta4)" }
[points]
Q = "a*exp(I*theta2)"
B = "zeta"
[output]
length = "in"
)toml";

// The message of the InputError that reading `text` throws ("" when it reads).
std::string error_of(const std::string& text, const std::string& name = "fb.toml") {
  try {
    read_mechanism_text(text, name);
  } catch (const kinema::InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("readers/mechanism_file: a full file is read in SI, in the order written, with lines") {
  const Mechanism m = read_mechanism_text(kFullText, "full.toml");
  CHECK(m.title == "reader test");
  CHECK(m.description == "all sections");
  CHECK(m.source_file == "full.toml");

  // Parameters in file order (not sorted, not hashed), each with its line.
  REQUIRE(m.parameters.size() == 6);
  const std::vector<std::string> names = {"zeta", "a", "m", "k", "g", "delta"};
  for (std::size_t i = 0; i < names.size(); ++i) {
    CAPTURE(i);
    CHECK(m.parameters[i].name == names[i]);
    CHECK(m.parameters[i].where.file == "full.toml");
    CHECK(m.parameters[i].where.line == static_cast<int>(4 + i));
  }
  CHECK(m.parameters[0].where.str() == "full.toml:4");
  REQUIRE(m.parameters[0].quantity);
  CHECK(m.parameters[0].quantity->si_value == doctest::Approx(2 * 0.0254).epsilon(1e-15));
  CHECK(m.parameters[0].quantity->dimension == Dimension::length);
  CHECK(m.parameters[0].text == "2 in");
  REQUIRE(m.parameters[1].quantity);
  CHECK(m.parameters[1].quantity->si_value == doctest::Approx(0.04).epsilon(1e-15));
  // A formula is kept as written, with no quantity.
  CHECK_FALSE(m.parameters[2].quantity);
  CHECK(m.parameters[2].formula == "a/2");
  // TOML numbers: an integer and a float, plain numbers, read exactly.
  REQUIRE(m.parameters[3].quantity);
  CHECK(m.parameters[3].quantity->dimension == Dimension::number);
  CHECK(m.parameters[3].quantity->si_value == 3.0);
  REQUIRE(m.parameters[4].quantity);
  CHECK(m.parameters[4].quantity->si_value == 0.1);
  REQUIRE(m.parameters[5].quantity);
  CHECK(m.parameters[5].quantity->dimension == Dimension::angle);
  CHECK(m.parameters[5].quantity->si_value == doctest::Approx(30 * kDeg).epsilon(1e-15));

  // The input: values in radians, rpm to rad/s, the names the file gives.
  CHECK(m.input.name == "theta2");
  CHECK(m.input.dimension == Dimension::angle);
  REQUIRE(m.input.values.size() == 2);
  CHECK(m.input.values[0] == doctest::Approx(30 * kDeg).epsilon(1e-15));
  CHECK(m.input.values[1] == doctest::Approx(0.5).epsilon(1e-15));
  CHECK(m.input.rate == doctest::Approx(2 * M_PI).epsilon(1e-15));
  CHECK(m.input.second_rate == doctest::Approx(2.0).epsilon(1e-15));
  CHECK(m.input.rate_name == "w2");
  CHECK(m.input.second_rate_name == "al2");
  CHECK(m.input.where.line == 11);  // the name's line

  // Unknowns in file order; an inline table carries the guess, rate names and LaTeX name.
  REQUIRE(m.unknowns.size() == 3);
  CHECK(m.unknowns[0].name == "theta4");
  CHECK(m.unknowns[1].name == "theta3");
  CHECK(m.unknowns[2].name == "s");
  CHECK(m.unknowns[0].dimension == Dimension::angle);
  CHECK(m.unknowns[0].guess == doctest::Approx(80 * kDeg).epsilon(1e-15));
  CHECK(m.unknowns[0].rate_name.empty());  // default names are chosen later (planar_loops)
  CHECK(m.unknowns[0].where.line == 18);
  CHECK(m.unknowns[1].where.line == 19);
  CHECK(m.unknowns[2].dimension == Dimension::length);
  CHECK(m.unknowns[2].guess == doctest::Approx(0.05).epsilon(1e-15));
  CHECK(m.unknowns[2].rate_name == "sd");
  CHECK(m.unknowns[2].second_rate_name == "sdd");
  CHECK(m.unknowns[2].latex_name == "\\varsigma");
  CHECK(m.unknowns[2].where.line == 20);

  // Loops: complex and by components, in file order.
  REQUIRE(m.loops.size() == 2);
  CHECK(m.loops[0].name == "Zloop");
  CHECK(m.loops[0].complex_formula == "a*exp(I*theta2) + s*exp(I*theta3) - zeta*exp(I*theta4) - m");
  CHECK(m.loops[0].x_formula.empty());
  CHECK(m.loops[0].where.line == 22);
  CHECK(m.loops[1].name == "Aloop");
  CHECK(m.loops[1].complex_formula.empty());
  CHECK(m.loops[1].x_formula == "a*cos(theta3) - s");
  CHECK(m.loops[1].y_formula == "zeta*sin(theta4)");
  CHECK(m.loops[1].where.line == 23);

  REQUIRE(m.points.size() == 2);
  CHECK(m.points[0].name == "Q");
  CHECK(m.points[1].name == "B");
  CHECK(m.points[1].formula == "zeta");
  CHECK(m.points[1].where.line == 26);

  CHECK(m.output.length == "in");
  CHECK(m.output.length_factor == doctest::Approx(0.0254).epsilon(1e-15));
}

TEST_CASE("readers/mechanism_file: defaults where the file says nothing") {
  const Mechanism m = read_mechanism_text(replaced("title = \"four-bar\"\n", ""), "fb.toml");
  CHECK(m.title == "Untitled mechanism");
  CHECK(m.description.empty());
  CHECK(m.output.length == "m");
  CHECK(m.output.length_factor == 1.0);
  CHECK(m.input.second_rate == 0.0);
  CHECK(m.input.rate == 10.0);
  REQUIRE(m.input.values.size() == 1);
  CHECK(m.input.values[0] == doctest::Approx(40 * kDeg).epsilon(1e-15));

  // Without any value the driver is still a crank (the command line gives the values).
  const Mechanism bare = read_mechanism_text(replaced("value = \"40 deg\"\n", ""), "fb.toml");
  CHECK(bare.input.values.empty());
  CHECK(bare.input.dimension == Dimension::angle);
}

TEST_CASE("readers/mechanism_file: sweeps under [input] become SI values, stop included") {
  const Mechanism angles = read_mechanism_text(replaced("value = \"40 deg\"", "sweep = \"0:90:30 deg\""), "fb.toml");
  REQUIRE(angles.input.values.size() == 4);
  for (int i = 0; i < 4; ++i) CHECK(angles.input.values[i] == doctest::Approx(30 * i * kDeg).epsilon(1e-15));

  // value and sweep together: the value first, then the sweep.
  const Mechanism both = read_mechanism_text(
      replaced("value = \"40 deg\"", "value = \"40 deg\"\nsweep = \"10:20:10 deg\""), "fb.toml");
  REQUIRE(both.input.values.size() == 3);
  CHECK(both.input.values[0] == doctest::Approx(40 * kDeg));
  CHECK(both.input.values[2] == doctest::Approx(20 * kDeg));

  // A length sweep makes a slider input, values in metres.
  const Mechanism slider = read_mechanism_text(
      replaced("rate = \"10 rad/s\"", "rate = \"2 m/s\"", replaced("value = \"40 deg\"", "sweep = \"150:170:10 mm\"")),
      "fb.toml");
  CHECK(slider.input.dimension == Dimension::length);
  CHECK(slider.input.rate == 2.0);
  REQUIRE(slider.input.values.size() == 3);
  CHECK(slider.input.values[0] == doctest::Approx(0.15).epsilon(1e-15));
  CHECK(slider.input.values[2] == doctest::Approx(0.17).epsilon(1e-15));
}

TEST_CASE("readers/mechanism_file: parse_sweep in a unit, steps that do not divide evenly, bad text") {
  const auto inches = kinema::parse_sweep("0:2:0.5", 0.0254).to_vector();
  REQUIRE(inches.size() == 5);
  for (std::size_t i = 0; i < inches.size(); ++i) CHECK(inches[i] == doctest::Approx(0.5 * i * 0.0254).epsilon(1e-15));

  // 0.1 is not exact in binary: (1 - 0) / 0.1 is 10 and a bit; still 11 values, stop included.
  const auto tenths = kinema::parse_sweep("0:1:0.1", 1.0).to_vector();
  REQUIRE(tenths.size() == 11);
  CHECK(tenths.back() == doctest::Approx(1.0).epsilon(1e-15));
  // A step that overshoots stops before the stop value.
  const auto uneven = kinema::parse_sweep("0:10:4", 1.0).to_vector();
  CHECK(uneven == std::vector<double>{0, 4, 8});
  CHECK(kinema::parse_sweep("5:5:1", 1.0).to_vector() == std::vector<double>{5});
  CHECK(kinema::parse_sweep(" 0 : 10 : 5 ", 1.0).size() == 3);

  for (const char* bad : {"0:10", "0:10:5:1", "0:10:5x", "a:10:1", "0;10;1", ""}) {
    CAPTURE(bad);
    CHECK_THROWS_WITH_AS(kinema::parse_sweep(bad, 1.0), doctest::Contains("start:stop:step"), kinema::InputError);
  }
  CHECK_THROWS_WITH_AS(kinema::parse_sweep("10:0:1", 1.0), doctest::Contains("never reaches its stop"),
                       kinema::InputError);
  CHECK_THROWS_AS(kinema::parse_sweep("0:1e9:1", 1.0), kinema::InputError);  // more than 10^7 values
  CHECK_THROWS_WITH_AS(kinema::parse_sweep("0:360:0.00001", 1.0),
                       doctest::Contains("more than 10000000 values"), kinema::InputError);  // a file's values are held
  CHECK(kinema::parse_sweep("0:359.99999:0.00036", 1.0).size() == 1000000);
  // A command-line sweep is streamed: 10^8 values are a sweep, not a vector (nothing allocated).
  const kinema::InputValues streamed = kinema::parse_sweep("0:360:0.0000036", 1.0, kinema::kMaxSweepValues);
  CHECK(streamed.size() == 100000001);
  CHECK(streamed.is_sweep());
  CHECK(streamed[100000000] == doctest::Approx(360));
  CHECK_THROWS_WITH_AS(kinema::parse_sweep("0:1e10:1", 1.0, kinema::kMaxSweepValues),
                       doctest::Contains("more than 1000000000 values"), kinema::InputError);
}

TEST_CASE("readers/mechanism_file: errors name file:line and what to write") {
  struct Case {
    std::string text;
    std::vector<std::string> expected;  // substrings of the message
  };
  const std::vector<Case> cases = {
      {replaced("b = \"120 mm\"", "b = \"120 mm"), {"fb.toml:4", "syntax error"}},
      {replaced("title = \"four-bar\"", "title = \"four-bar\"\ncolour = \"red\""),
       {"fb.toml:2", "unknown key \"colour\"", "expected one of"}},
      {replaced("rate = \"10 rad/s\"", "rate = \"10 rad/s\"\nspeed = \"3\""), {"fb.toml:11", "unknown key \"speed\""}},
      {replaced("rate = \"10 rad/s\"", "rate = \"10 mm\""), {"fb.toml:10", "rate", "length"}},
      {replaced("a = \"40 mm\"", "a = \"40 furlongs\""), {"fb.toml:3", "furlongs"}},
      {replaced("theta3 = \"20 deg\"", "a = \"20 deg\""),
       {"fb.toml:12", "duplicate name \"a\"", "already defined at fb.toml:3"}},
      {replaced("d = \"100 mm\"", "sin = \"100 mm\""), {"fb.toml:6", "reserved"}},
      {replaced("d = \"100 mm\"", "2d = \"100 mm\""), {"fb.toml:6", "not a valid name"}},
      {replaced("theta3 = \"20 deg\"", "theta3 = \"20\""), {"fb.toml:12", "angle or a length unit"}},
      {replaced("rate = \"10 rad/s\"\n", ""), {"fb.toml:8", "needs rate"}},
      {replaced("name = \"theta2\"\n", ""), {"fb.toml", "needs name"}},
      {replaced("[input]\nname = \"theta2\"\nvalue = \"40 deg\"\nrate = \"10 rad/s\"\n", ""),
       {"fb.toml", "[input] is missing"}},
      {replaced("value = \"40 deg\"", "values = \"40 deg\""), {"fb.toml:9", "must be a list"}},
      {replaced("value = \"40 deg\"", "value = \"40 rad/s\""), {"fb.toml:9", "angle", "length"}},
      {replaced("value = \"40 deg\"", "values = [\"40 deg\", \"10 mm\"]"), {"fb.toml:9", "mixes angles and lengths"}},
      {replaced("value = \"40 deg\"", "sweep = \"0:90:10\""), {"fb.toml:9", "sweep needs a unit"}},
      {replaced("value = \"40 deg\"", "sweep = \"0:90 deg\""), {"fb.toml:9", "start:stop:step"}},
      {replaced("value = \"40 deg\"", "sweep = \"0:90:10 rad/s\""), {"fb.toml:9", "angle or a length unit"}},
      {replaced("value = \"40 deg\"", "value = \"40 deg\"\nsweep = \"0:10:1 mm\""), {"fb.toml:10", "mixes"}},
      {replaced("ABCD = \"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d\"",
                "ABCD = { x = \"a*cos(theta2) - d\" }"),
       {"fb.toml:15", "needs both"}},
      {replaced("theta3 = \"20 deg\"\ntheta4 = \"80 deg\"\n", ""), {"fb.toml:11", "[unknowns] is empty"}},
      {four_bar_text() + "[output]\nlength = \"furlong\"\n", {"fb.toml:19", "furlong"}},
      {four_bar_text() + "[output]\nlength = \"mm\"\nangle = \"rad\"\n", {"fb.toml:20", "unknown key \"angle\""}},
      {replaced("title = \"four-bar\"", "title = 3"), {"fb.toml:1", "must be a string"}},
      {replaced("a = \"40 mm\"", "a = true"), {"fb.toml:3", "must be a string"}},
      {replaced("theta3 = \"20 deg\"", "theta3 = { rate_name = \"w3\" }"), {"fb.toml:12", "needs guess"}},
  };
  for (const Case& c : cases) {
    const std::string message = error_of(c.text);
    CAPTURE(c.text);
    CAPTURE(message);
    REQUIRE_FALSE(message.empty());
    for (const std::string& part : c.expected) {
      CAPTURE(part);
      CHECK(message.find(part) != std::string::npos);
    }
  }
  // The good text itself reads (the cases above fail for the reason given, not for another).
  CHECK(error_of(four_bar_text()).empty());
}

TEST_CASE("readers/mechanism_file: reading a file that does not exist names it") {
  CHECK_THROWS_WITH_AS(kinema::read_mechanism_file("/nonexistent/dir/mech.toml"),
                       doctest::Contains("/nonexistent/dir/mech.toml"), kinema::InputError);
  // And a file on disk reads like the same text in memory.
  const std::string path = kinema_test::write_temporary("unit_reader.toml", four_bar_text());
  const Mechanism from_file = kinema::read_mechanism_file(path);
  CHECK(from_file.source_file == path);
  REQUIRE(from_file.parameters.size() == 4);
  CHECK(from_file.parameters[3].where.str() == path + ":6");
}

TEST_CASE("readers/mechanism_file: a sweep in a unit that is not understood names file:line") {
  // Every other unit error carries file:line; the sweep's unit is parsed outside the
  // wrapper that adds it (FileReader::read_input), so this one did not.
  const std::string message = error_of(replaced("value = \"40 deg\"", "sweep = \"0:90:10 furlongs\""));
  CAPTURE(message);
  CHECK(message.find("furlongs") != std::string::npos);
  CHECK(message.find("fb.toml:9") != std::string::npos);
}

// Reading gives what the user wrote; the loops and dyads of joints and links are their
// front end's, built as a separate step (engine/model.hpp, build_constraint_system).
TEST_CASE("readers/mechanism_file: a joints-and-links file is read as written, and no front end runs") {
  const Mechanism m = kinema::read_mechanism_file(kinema_test::sample("problem_4_4_joints.toml"));
  REQUIRE(m.linkage);
  CHECK(m.linkage->joints.size() == 7);
  CHECK(m.input.name == "phi");  // as the file names the driver's angle
  CHECK(m.unknowns.empty());
  CHECK(m.loops.empty());
  CHECK(m.points.empty());
  const kinema::ConstraintSystem system = kinema::build_constraint_system(m);
  REQUIRE(system.groups.size() == 2);
  CHECK(system.groups[0].name == "ABCD");
  CHECK(system.groups[1].name == "D_E_F_F5");
  CHECK(system.equations.size() == 4);
  REQUIRE(system.plan);
  CHECK(system.plan->closed_form);
  CHECK(system.plan->dyads.size() == 2);
}

TEST_CASE("every file kinema reads is refused alike: a directory, a missing path, one past its size limit") {
  // Mechanism files, answers files and class tables share readers/file_reader's read_text_file.
  const std::string directory = kinema_test::fresh_directory("read_text_file");
  const std::string missing = directory + "/absent.toml";
  struct Reader {
    const char* what;
    std::function<void(const std::string&)> read;
  };
  const std::vector<Reader> readers{
      {"mechanism file", [](const std::string& path) { kinema::read_mechanism_file(path); }},
      {"answers file", [](const std::string& path) { kinema::read_answers_file(path); }},
      {"class table", [](const std::string& path) { kinema::read_class_table(path); }}};
  auto message = [](const Reader& reader, const std::string& path) {
    try {
      reader.read(path);
    } catch (const kinema::InputError& error) {
      return std::string(error.what());
    }
    return std::string("read");
  };
  for (const Reader& reader : readers) {
    CAPTURE(reader.what);
    const std::string what = reader.what;
    CHECK(message(reader, directory).find(": is a directory, not a") != std::string::npos);
    CHECK(message(reader, directory).find(what) != std::string::npos);
    CHECK(message(reader, missing).find("cannot open the " + what) != std::string::npos);
    // /dev/zero never ends: the read stops past the limit.
    CHECK(message(reader, "/dev/zero").find("the " + what + " is larger than") != std::string::npos);
  }
  CHECK(message(readers[1], directory).find("not an answers file") != std::string::npos);
}
