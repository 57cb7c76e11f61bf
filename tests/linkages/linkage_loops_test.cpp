// linkages/linkage_loops: a mechanism written as joints and links is written as vector
// loops that give the numbers of the loops a student writes by hand (the bundled
// joints-and-links samples against their hand-written twins, over whole sweeps),
// the loop file it writes reads back to the same numbers, and every structural
// mistake is refused with file:line, the names, and what to change.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <sstream>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/base/errors.hpp"
#include "engine/base/work_count.hpp"
#include "engine/model.hpp"
#include "engine/printers/printer.hpp"
#include "linkages/linkage_loops.hpp"
#include "loops/planar_loops.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

using kinema::MotionTable;
using kinema::Model;
using kinema_test::sample;

namespace {

// The crank-rocker of samples/four_bar.toml, as drawn, at theta2 = 40 deg.
const std::string kFourBar = R"(title = "four-bar as drawn"
[parameters]
a = "40 mm"
b = "120 mm"
c = "80 mm"
[joints]
A = { ground = true, at = ["0 mm", "0 mm"] }
B = { at = ["30.6417777 mm", "25.7115044 mm"] }
C = { at = ["143.189988 mm", "67.3396237 mm"] }
D = { ground = true, at = ["100 mm", "0 mm"] }
[links]
2 = { joints = ["A", "B"], length = "a" }
3 = { joints = ["B", "C"], length = "b" }
4 = { joints = ["D", "C"], length = "c" }
[driver]
link = "2"
value = "40 deg"
rate = "10 rad/s"
)";

Model model_of(const std::string& text) { return kinema::make_model(kinema::read_mechanism_text(text, "lk.toml")); }

std::string error_of(const std::string& text) {
  try {
    model_of(text);
  } catch (const kinema::InputError& error) {
    return error.what();
  }
  return "";
}

std::string edited(const std::string& from, const std::string& to, std::string text = kFourBar) {
  const auto at = text.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, from);
  return text.replace(at, from.size(), to);
}

std::vector<double> degrees(double from, double to, double step) {
  std::vector<double> values;
  for (double d = from; d <= to + 1e-9; d += step) values.push_back(d * M_PI / 180);
  return values;
}

double coordinate_value(const Model& model, const MotionTable& table, std::size_t row, const std::string& name, int order) {
  const auto& unknowns = model.system.unknowns;
  for (std::size_t i = 0; i < unknowns.size(); ++i) {
    if (unknowns[i].name != name) continue;
    const auto at = Eigen::Index(i);
    return order == 0 ? table.q(row)[at] : order == 1 ? table.qd(row)[at] : table.qdd(row)[at];
  }
  FAIL("no coordinate " << name);
  return 0;
}

std::size_t point_index(const Model& model, const std::string& name) {
  for (std::size_t p = 0; p < model.system.points.size(); ++p)
    if (model.system.points[p].name == name) return p;
  FAIL("no point " << name);
  return 0;
}

// Every coordinate and every point of `hand` equal in `drawn`, row by row.
void check_same_motion(const Model& drawn, const Model& hand, const std::vector<double>& inputs) {
  const MotionTable a = kinema::solve_motion(drawn, inputs), b = kinema::solve_motion(hand, inputs);
  for (std::size_t row = 0; row < inputs.size(); ++row) {
    CAPTURE(inputs[row] * 180 / M_PI);
    REQUIRE(a.status(row) == b.status(row));
    if (a.status(row) != kinema::Status::ok) continue;
    for (const auto& u : hand.system.unknowns) {
      CAPTURE(u.name);
      for (int order = 0; order < 3; ++order) {
        const double x = coordinate_value(drawn, a, row, u.name, order), y = coordinate_value(hand, b, row, u.name, order);
        const double scale = std::max(1.0, std::fabs(y));
        // Angles may differ by whole turns (the sketch's angle against a guess).
        const double difference = order == 0 && u.dimension == kinema::Dimension::angle
                                      ? std::remainder(x - y, 2 * M_PI)
                                      : x - y;
        CHECK(std::fabs(difference) <= 1e-9 * scale);
      }
    }
    for (std::size_t p = 0; p < hand.system.points.size(); ++p) {
      const auto& name = hand.system.points[p].name;
      CAPTURE(name);
      const kinema::PointMotion x = a.point(row, point_index(drawn, name)), y = b.point(row, p);
      for (std::size_t c = 0; c < 2; ++c) {
        CHECK(std::fabs(x.position[c] - y.position[c]) <= 1e-9 * (1 + std::fabs(y.position[c])));
        CHECK(std::fabs(x.velocity[c] - y.velocity[c]) <= 1e-9 * (1 + std::fabs(y.velocity[c])));
        CHECK(std::fabs(x.acceleration[c] - y.acceleration[c]) <= 1e-9 * (1 + std::fabs(y.acceleration[c])));
      }
    }
  }
}

}  // namespace

TEST_CASE("linkages/linkage_loops: Problem 4.4 as drawn moves as its hand-written loops, over the whole crank turn") {
  const Model drawn = kinema::load_model(sample("problem_4_4_joints.toml"));
  const Model hand = kinema::load_model(sample("problem_4_4_six_bar.toml"));
  // The loops found: one per joint outside the spanning tree (7 joints, 6 bodies: two).
  REQUIRE(drawn.system.groups.size() == 2);
  CHECK(drawn.system.groups[0].name == "ABCD");
  CHECK(drawn.system.groups[1].name == "D_E_F_F5");
  check_same_motion(drawn, hand, degrees(0, 360, 7.5));
}

TEST_CASE("linkages/linkage_loops: Example 4.1 as drawn (a slider on the moving crank) moves as its loop") {
  const Model drawn = kinema::load_model(sample("example_4_1_joints.toml"));
  const Model hand = kinema::load_model(sample("example_4_1_r_trr.toml"));
  check_same_motion(drawn, hand, degrees(20, 160, 5));
}

TEST_CASE("linkages/linkage_loops: Example 4.2 as drawn (a slider on the turning link 3) moves as its loops") {
  const Model drawn = kinema::load_model(sample("example_4_2_joints.toml"));
  const Model hand = kinema::load_model(sample("example_4_2_r_rtr_rrt.toml"));
  check_same_motion(drawn, hand, degrees(0, 360, 10));
  const MotionTable t = kinema::solve_motion(drawn, {M_PI / 4});
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "phi3", 1), "1.807");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "phi3", 2), "1.020");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "phi4", 1), "0.221");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "phi4", 2), "-1.105");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "xE", 0), "0.164");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "xE", 1), "0.113");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "xE", 2), "0.217");
  const kinema::PointMotion d = t.point(0, point_index(drawn, "D"));
  CHECK_PRINTED(d.velocity[0], "0.129");
  CHECK_PRINTED(d.velocity[1], "-0.041");
  CHECK_PRINTED(d.acceleration[0], "0.147");
  CHECK_PRINTED(d.acceleration[1], "0.210");
}

TEST_CASE("linkages/linkage_loops: Problem 3.22 as drawn (a triangle coupler, two sliders, inches) moves as its loops") {
  const Model drawn = kinema::load_model(sample("problem_3_22_joints.toml"));
  const Model hand = kinema::load_model(sample("problem_3_22_six_bar_sliders.toml"));
  // The angle beta stays the file's formula in the loop it writes.
  CHECK(drawn.system.groups.at(1).name == "O2_A_C_D_D6");
  const auto loops = kinema_test::loops_file(kinema::read_mechanism_file(sample("problem_3_22_joints.toml")));
  CHECK(loops.find("a*exp(I*(theta3 + beta))") != std::string::npos);
  check_same_motion(drawn, hand, degrees(-180, 180, 15));
  const MotionTable t = kinema::solve_motion(drawn, {-120 * M_PI / 180});
  const double inch = 0.0254;
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "theta3", 1), "-4.26");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "r1", 1) / inch, "-65.3");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "theta5", 1), "-7.67");
  CHECK_PRINTED(coordinate_value(drawn, t, 0, "r6", 1) / inch, "22.25");
  const kinema::PointMotion c = t.point(0, point_index(drawn, "C"));
  CHECK_PRINTED(c.velocity[0] / inch, "-60.90");  // the seed's -60.89: see the sample
  CHECK_PRINTED(c.velocity[1] / inch, "29.73");
}

TEST_CASE("linkages/linkage_loops: the vector-loop file kinema writes reads back to the same numbers") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml"}) {
    CAPTURE(name);
    const kinema::Mechanism drawn = kinema::read_mechanism_file(sample(name));
    const std::string loops = kinema_test::loops_file(drawn);
    CHECK(loops.find("[joints]") == std::string::npos);
    const kinema::Mechanism again = kinema::read_mechanism_text(loops, "loops.toml");
    CHECK_FALSE(again.linkage);
    check_same_motion(kinema::make_model(drawn), kinema::make_model(again), degrees(10, 350, 20));
  }
}

namespace {

// `b` with `a`'s symbols put in for theirs by name (two systems, each with symbols of its own).
GiNaC::ex in_symbols_of(const kinema::ConstraintSystem& a, const kinema::ConstraintSystem& b, const GiNaC::ex& e) {
  GiNaC::exmap same;
  for (std::size_t k = 0; k < b.parameters.size(); ++k) same[b.parameters[k].symbol] = a.parameters.at(k).symbol;
  same[b.input.symbol] = a.input.symbol;
  same[b.input.rate] = a.input.rate;
  same[b.input.second_rate] = a.input.second_rate;
  for (std::size_t k = 0; k < b.unknowns.size(); ++k) {
    same[b.unknowns[k].symbol] = a.unknowns.at(k).symbol;
    same[b.unknowns[k].rate] = a.unknowns.at(k).rate;
    same[b.unknowns[k].second_rate] = a.unknowns.at(k).second_rate;
  }
  return e.subs(same, GiNaC::subs_options::no_pattern);
}

// Each expression of `read` is, in `built`'s symbols, the same expression (not merely equal
// when expanded: GiNaC's canonical form, so that every view prints the same).
void check_same_expressions(const kinema::ConstraintSystem& built, const kinema::ConstraintSystem& read) {
  const auto same = [&](const GiNaC::ex& x, const GiNaC::ex& y) { return x.is_equal(in_symbols_of(built, read, y)); };
  REQUIRE(built.parameters.size() == read.parameters.size());
  for (std::size_t k = 0; k < read.parameters.size(); ++k)
    CHECK(built.parameters[k].symbol.get_name() == read.parameters[k].symbol.get_name());
  REQUIRE(built.unknowns.size() == read.unknowns.size());
  for (std::size_t k = 0; k < read.unknowns.size(); ++k) CHECK(built.unknowns[k].name == read.unknowns[k].name);
  REQUIRE(built.equations.size() == read.equations.size());
  for (std::size_t k = 0; k < read.equations.size(); ++k) CHECK(same(built.equations[k].expression, read.equations[k].expression));
  REQUIRE(built.groups.size() == read.groups.size());
  for (std::size_t g = 0; g < read.groups.size(); ++g) {
    CAPTURE(read.groups[g].name);
    CHECK(built.groups[g].name == read.groups[g].name);
    REQUIRE((built.groups[g].vector && read.groups[g].vector));
    CHECK(same(*built.groups[g].vector, *read.groups[g].vector));
    REQUIRE(built.groups[g].terms.size() == read.groups[g].terms.size());
    for (std::size_t t = 0; t < read.groups[g].terms.size(); ++t) CHECK(same(built.groups[g].terms[t], read.groups[g].terms[t]));
  }
  REQUIRE(built.points.size() == read.points.size());
  for (std::size_t p = 0; p < read.points.size(); ++p) {
    const auto &x = built.points[p], &y = read.points[p];
    CAPTURE(y.name);
    CHECK(x.name == y.name);
    CHECK(x.is_joint == y.is_joint);
    REQUIRE((x.written && y.written));
    CHECK(same(*x.written, *y.written));
    for (std::size_t c = 0; c < 2; ++c) CHECK(same(x.position.at(c), y.position.at(c)));
    REQUIRE(x.written_terms.size() == y.written_terms.size());
    for (std::size_t t = 0; t < y.written_terms.size(); ++t) CHECK(same(x.written_terms[t], y.written_terms[t]));
  }
}

}  // namespace

TEST_CASE("linkages/linkage_loops: the expressions built from the terms are those the loops' text reads to") {
  std::vector<kinema::Mechanism> drawn;
  for (const char* name : kinema_test::kSamples) {
    kinema::Mechanism m = kinema::read_mechanism_file(sample(name));
    if (m.linkage) drawn.push_back(m);
  }
  REQUIRE(drawn.size() >= 7);
  // A length written as a formula (with a number in it) and an angle from the sketch.
  drawn.push_back(kinema::read_mechanism_text(edited("length = \"b\"", "length = \"3*a\""), "lk.toml"));
  REQUIRE(kinema::linkage_loops(drawn.back()).loops.loops.at(0).complex_formula.find("(3*a)*exp(I*theta3)") !=
          std::string::npos);
  for (const kinema::Mechanism& m : drawn) {
    CAPTURE(m.source_file);
    const kinema::ConstraintSystem built = kinema::build_linkage_system(m);
    const kinema::ConstraintSystem read = kinema::build_planar_loops(kinema::linkage_loops(m).loops);
    check_same_expressions(built, read);
  }
}

TEST_CASE("linkages/linkage_loops: no text is read to build a joints-and-links file's equations") {
  using kinema::Work;
  const auto reads_in = [](const std::string& path) {
    const kinema::Mechanism m = kinema::read_mechanism_file(path);
    const std::uint64_t before = kinema::work_done_in_process(Work::formula_read);
    kinema::make_model(m);
    return kinema::work_done_in_process(Work::formula_read) - before;
  };
  // Its parameters are quantities and its lengths their names: nothing the file writes is a formula.
  CHECK(reads_in(sample("problem_4_1_parallelogram.toml")) == 0);
  // Its vector-loop twin reads its loops and points (the counter counts).
  CHECK(reads_in(sample("four_bar.toml")) > 0);
}

TEST_CASE("linkages/linkage_loops: the four-bar as drawn: link angles from the sketch, lengths as given") {
  const kinema::Mechanism m = kinema::linkage_loops(kinema::read_mechanism_text(kFourBar, "lk.toml")).loops;
  REQUIRE(m.unknowns.size() == 2);
  CHECK(m.input.name == "theta2");
  CHECK(m.unknowns[0].name == "theta3");
  CHECK(m.unknowns[1].name == "theta4");
  // The sketch's angles are the guesses (the assembly branch is the sketch's).
  CHECK(m.unknowns[0].guess == doctest::Approx(20.2978828 * M_PI / 180).epsilon(1e-7));
  CHECK(m.unknowns[1].guess == doctest::Approx(57.3248801 * M_PI / 180).epsilon(1e-7));
  REQUIRE(m.loops.size() == 1);
  CHECK(m.loops[0].name == "ABCD");
  const Model model = kinema::make_model(m);
  const MotionTable t = kinema::solve_motion(model, {40 * M_PI / 180});
  REQUIRE(t.status(0) == kinema::Status::ok);
  CHECK(t.qd(0)[0] == doctest::Approx(-1.64836577).epsilon(1e-8));
  CHECK(t.qdd(0)[1] == doctest::Approx(74.5495583).epsilon(1e-8));
  // Every moving joint is a point.
  CHECK(model.system.points.size() == 2);
}

TEST_CASE("linkages/linkage_loops: Problem 4.4 as drawn reproduces the seed's numbers") {
  const Model model = kinema::load_model(sample("problem_4_4_joints.toml"));
  const MotionTable t = kinema::solve_motion(model, {M_PI / 6});
  REQUIRE(t.status(0) == kinema::Status::ok);
  CHECK_PRINTED(coordinate_value(model, t, 0, "phi2", 1), "-1.1307");
  CHECK_PRINTED(coordinate_value(model, t, 0, "phi3", 1), "-2.82169");
  CHECK_PRINTED(coordinate_value(model, t, 0, "phi4", 1), "0.58475");
  CHECK_PRINTED(coordinate_value(model, t, 0, "yF", 1), "1.64625");
  CHECK_PRINTED(coordinate_value(model, t, 0, "phi2", 2), "-22.33");
  CHECK_PRINTED(coordinate_value(model, t, 0, "phi3", 2), "-2.20443");
  CHECK_PRINTED(coordinate_value(model, t, 0, "phi4", 2), "-21.453");
  CHECK_PRINTED(coordinate_value(model, t, 0, "yF", 2), "3.29262");
  const kinema::PointMotion c = t.point(0, point_index(model, "C")), e = t.point(0, point_index(model, "E"));
  CHECK_PRINTED(c.position[0], "-0.0689445");
  CHECK_PRINTED(c.position[1], "0.422073");
  CHECK_PRINTED(e.position[0], "-0.298288");
  CHECK_PRINTED(e.position[1], "0.404712");
  CHECK_PRINTED(c.velocity[0], "-0.0788027");
  CHECK_PRINTED(c.velocity[1], "1.04105");
  CHECK_PRINTED(e.acceleration[0], "4.66371");
  CHECK_PRINTED(e.acceleration[1], "1.67947");
}

TEST_CASE("linkages/linkage_loops: structural mistakes are refused with file:line, the names and what to do") {
  SUBCASE("a pin used by one link only") {
    const std::string message = error_of(edited(R"(4 = { joints = ["D", "C"], length = "c" })", R"(4 = { joints = ["D", "E"] }
E = { joints = ["C"] })", edited(R"(D = { ground)", R"(E = { at = ["1 mm", "1 mm"] }
D = { ground)")));
    CHECK(message.find("lk.toml:") == 0);
    CHECK(message.find("is used by link") != std::string::npos);
  }
  SUBCASE("a joint on no link") {
    const std::string message = error_of(edited(R"(D = { ground)", R"(Q = { at = ["1 mm", "1 mm"] }
D = { ground)"));
    CHECK(message.find("lk.toml:10:") == 0);
    CHECK(message.find("\"Q\" is on no link") != std::string::npos);
  }
  SUBCASE("a joint a link lists that does not exist") {
    CHECK(error_of(edited(R"(["B", "C"], length = "b")", R"(["B", "X"], length = "b")"))
              .find("lists joint \"X\", which is not in [joints]") != std::string::npos);
  }
  SUBCASE("links that share no joint with the rest") {
    const std::string message = error_of(edited("[driver]", R"(5 = { joints = ["E", "F"] }
6 = { joints = ["F", "E"] }
[driver])", edited(R"(D = { ground)", R"(E = { at = ["1 mm", "1 mm"] }
F = { at = ["2 mm", "1 mm"] }
D = { ground)")));
    CHECK(message.find("lk.toml:") == 0);
    CHECK(message.find("links 5, 6 share no joint with the rest") != std::string::npos);
  }
  SUBCASE("mobility 2: a five-bar with one driver") {
    const std::string message = error_of(edited(R"(4 = { joints = ["D", "C"], length = "c" })",
                                                R"(4 = { joints = ["E", "C"] }
5 = { joints = ["D", "E"] })", edited(R"(D = { ground)", R"(E = { at = ["120 mm", "40 mm"] }
D = { ground)")));
    CHECK(message.find("lk.toml:") == 0);
    CHECK(message.find("mobility is 2") != std::string::npos);
    CHECK(message.find("3*4 - 2*5 = 2") != std::string::npos);
    CHECK(message.find("add 1 constraint") != std::string::npos);
  }
  SUBCASE("mobility 0: a triangle of links") {
    const std::string message = error_of(edited(R"(3 = { joints = ["B", "C"], length = "b" })",
                                                R"(3 = { joints = ["B", "C", "D"] })"));
    // D now joins ground, 3 and 4: two joints by Grübler's count.
    CHECK(message.find("mobility is -1") != std::string::npos);
    CHECK(message.find("it is a structure: remove 2 binary link(s)") != std::string::npos);
  }
  SUBCASE("a length that contradicts the sketch: both numbers") {
    const std::string message = error_of(edited(R"(b = "120 mm")", R"(b = "150 mm")"));
    CHECK(message.find("lk.toml:") == 0);
    CHECK(message.find("link \"3\": the length B-C = \"b\" is 0.15 m, but the sketch puts B and C 0.12 m apart") !=
          std::string::npos);
  }
  SUBCASE("a driver that is not attached to ground") {
    const std::string message = error_of(edited(R"(link = "2")", R"(link = "3")"));
    CHECK(message.find("lk.toml:15:") == 0);
    CHECK(message.find("the driver, link \"3\", is not attached to ground") != std::string::npos);
  }
  SUBCASE("a driver that is no link") {
    CHECK(error_of(edited(R"(link = "2")", R"(link = "9")")).find("[driver] link = \"9\" is not a link") !=
          std::string::npos);
  }
  SUBCASE("a crank driven with a length") {
    CHECK(error_of(edited(R"(value = "40 deg")", R"(value = "40 mm")")).find("its values are angles") != std::string::npos);
  }
  SUBCASE("reserved and duplicate names") {
    CHECK(error_of(edited(R"(B = { at)", R"(sin = { at)")).find("joint name \"sin\" is reserved") != std::string::npos);
    CHECK(error_of(edited(R"(length = "b" })", R"(length = "b", angle = "a" })"))
              .find("duplicate name \"a\"") != std::string::npos);
  }
  SUBCASE("a parameter formula that cannot be evaluated (fuzzing: a length that underflows to 0 under a division)") {
    const std::string message = error_of(edited(R"(c = "80 mm")", R"x(c = "1e-30010 mm"
k = "asin(a/c)")x"));
    CHECK(message.find("lk.toml:6: parameter \"k\" = \"asin(a/c)\" cannot be evaluated") == 0);
  }
  SUBCASE("more joints or links than a mechanism has") {
    std::string joints, links;
    for (int k = 0; k < 129; ++k) joints += "J" + std::to_string(k) + " = { at = [\"0 mm\", \"0 mm\"] }\n";
    CHECK(error_of(edited("[links]", joints + "[links]")).find("[joints] has 133 joints; kinema takes up to 128") !=
          std::string::npos);
    for (int k = 0; k < 62; ++k) links += "L" + std::to_string(k) + " = { joints = [\"B\", \"C\"] }\n";
    CHECK(error_of(edited("[driver]", links + "[driver]")).find("[links] has 65 links; kinema takes up to 64") !=
          std::string::npos);
  }
  SUBCASE("vector loops and joints in one file") {
    CHECK(error_of(edited("[driver]", "[loops]\nX = \"a\"\n[driver]"))
              .find("unknown key \"loops\" in the top level of a joints-and-links file") != std::string::npos);
  }
  SUBCASE("a slider off its line, a slider on no link, a slider on a missing guide") {
    // A slider-crank: the rocker 4 and its pivot D replaced by a block on a fixed line.
    const std::string slider_crank = edited(R"(4 = { joints = ["D", "C"], length = "c" })", R"(5 = { joints = ["C", "S"] })",
                                            edited(R"(D = { ground = true, at = ["100 mm", "0 mm"] })",
                                                   R"(S = { slider = "ground", at = ["143.189988 mm", "67.3396237 mm"], angle = "0 deg", through = ["0 mm", "67.3396237 mm"] })"));
    CHECK(error_of(slider_crank).empty());
    const std::string off = edited(R"(through = ["0 mm", "67.3396237 mm"])", R"(through = ["0 mm", "60 mm"])", slider_crank);
    const std::string message = error_of(off);
    CHECK(message.find("lk.toml:10:") == 0);
    CHECK(message.find("slider \"S\": its place in the sketch is 0.00733962 m off its line") != std::string::npos);
    CHECK(error_of(edited(R"(slider = "ground")", R"(slider = "7")", slider_crank)).find("slides on \"7\", which is not a link") !=
          std::string::npos);
    CHECK(error_of(edited(R"(5 = { joints = ["C", "S"] })", R"(5 = { joints = ["C"] })", slider_crank))
              .find("slider \"S\" is on no link") != std::string::npos);
    // Session 30's review: an angle of 1e300 deg was "0.12391 m off its line".
    CHECK(error_of(edited(R"(angle = "0 deg")", R"(angle = "1e300 deg")", slider_crank))
              .find("slider \"S\": angle = \"1e300 deg\" is past 1e9 deg") != std::string::npos);
    CHECK(error_of(edited(R"(angle = "0 deg")", R"(angle = "720 deg")", slider_crank)).empty());
    // Session 30's review: a guide that is the block itself was "on no link", though listed.
    CHECK(error_of(edited(R"(slider = "ground")", R"(slider = "5")", slider_crank))
              .find("slider \"S\" slides on \"5\", the only link that lists it: its block cannot be its guide") !=
          std::string::npos);
  }
}

TEST_CASE("linkages/linkage_loops: the solving order is the seeds': driver, then dyads named by their joints") {
  struct Expected {
    const char* sample;
    std::vector<std::string> kinds;
    std::vector<std::vector<std::string>> joints;
  };
  const std::vector<Expected> cases = {
      {"problem_4_4_joints.toml", {"driver", "RRR", "RRT"}, {{"A"}, {"B", "C", "D"}, {"E", "F", "F5"}}},  // R-RRR-RRT
      {"example_4_1_joints.toml", {"driver", "TRR"}, {{"A"}, {"B2", "B", "C"}}},                           // R-TRR
      {"example_4_2_joints.toml", {"driver", "RTR", "RRT"}, {{"A"}, {"B", "B2", "C"}, {"D", "E", "E5"}}},  // R-RTR-RRT
      {"problem_3_22_joints.toml", {"driver", "RRT", "RRT"}, {{"O2"}, {"A", "B", "B4"}, {"C", "D", "D6"}}},
  };
  for (const Expected& expected : cases) {
    CAPTURE(expected.sample);
    const kinema::ConstraintSystem m = kinema::build_constraint_system(kinema::read_mechanism_file(sample(expected.sample)));
    REQUIRE(m.plan);
    REQUIRE(m.plan->steps.size() == expected.kinds.size());
    for (std::size_t k = 0; k < expected.kinds.size(); ++k) {
      CHECK(m.plan->steps[k].kind == expected.kinds[k]);
      CHECK(m.plan->steps[k].joints == expected.joints[k]);
    }
    CHECK(3 * (m.plan->body_count - 1) - 2 * m.plan->joint_count == 1);
  }
  // derive prints it, in text and LaTeX.
  const Model model = kinema::load_model(sample("problem_4_4_joints.toml"));
  std::ostringstream text, latex;
  kinema::print_view(*kinema::find_printer(kinema::PrintKind::derivation, "text"), text, {model});
  kinema::print_view(*kinema::find_printer(kinema::PrintKind::derivation, "latex"), latex, {model});
  CHECK(text.str().find("dyad 1, RRR: links 2, 3; joints B, C, D") != std::string::npos);
  CHECK(text.str().find("dyad 2, RRT: links 4, 5; joints E, F, F5") != std::string::npos);
  CHECK(text.str().find("3(n - 1) - 2j = 3*5 - 2*7 = 1") != std::string::npos);
  CHECK(text.str().find("independent loops (one per joint outside a spanning tree from ground): ABCD, D_E_F_F5") !=
        std::string::npos);
  // (as text between the blocks' rows, where it wraps)
  CHECK(latex.str().find("\\\\\ndyad 2, RRT: links 4, 5; joints E, F, F5") != std::string::npos);
  // A vector-loop file has no structure section.
  std::ostringstream loops_text;
  kinema::print_view(*kinema::find_printer(kinema::PrintKind::derivation, "text"), loops_text, {kinema::load_model(sample("problem_4_4_six_bar.toml"))});
  CHECK(loops_text.str().find("Structure") == std::string::npos);
}

TEST_CASE("linkages/linkage_loops: at each slider the relative velocity, relative and Coriolis accelerations, as the seeds print them") {
  // Example 4.1: B2 slides on the crank 1.
  const nlohmann::json e41 = kinema_test::eval_json("example_4_1_joints.toml").at("results").at(0);
  const nlohmann::json& b2 = e41.at("sliders").at("B2");
  CHECK_PRINTED(b2.at("relative_velocity")[0].get<double>(), "-0.195");
  CHECK_PRINTED(b2.at("relative_velocity")[1].get<double>(), "-0.195");
  CHECK_PRINTED(b2.at("relative_acceleration")[0].get<double>(), "-0.5");
  CHECK_PRINTED(b2.at("relative_acceleration")[1].get<double>(), "-0.5");
  CHECK_PRINTED(b2.at("coriolis")[0].get<double>(), "1.226");
  CHECK_PRINTED(b2.at("coriolis")[1].get<double>(), "-1.226");
  // The block 2 turns with the crank; omega23 = omega2 - omega3, alpha23 = alpha2 - alpha3.
  const nlohmann::json& block2 = e41.at("blocks").at("2");
  CHECK(block2.at("rate").get<double>() == doctest::Approx(3.141));
  const nlohmann::json& link3 = e41.at("coordinates").at("phi3");
  CHECK_PRINTED(block2.at("rate").get<double>() - link3.at("rate").get<double>(), "-0.762");
  CHECK_PRINTED(block2.at("second_rate").get<double>() - link3.at("second_rate").get<double>(), "2.252");

  // Example 4.2: B2 slides on link 3.
  const nlohmann::json e42 = kinema_test::eval_json("example_4_2_joints.toml").at("results").at(0);
  const nlohmann::json& s = e42.at("sliders").at("B2");
  CHECK_PRINTED(s.at("relative_velocity")[0].get<double>(), "0.065");
  CHECK_PRINTED(s.at("relative_velocity")[1].get<double>(), "0.205");
  CHECK_PRINTED(s.at("coriolis")[0].get<double>(), "-0.742");
  CHECK_PRINTED(s.at("coriolis")[1].get<double>(), "0.237");
  // The seed ends a_B23 = -1.569i - 1.569j - (-0.456i - 0.649j) - (-0.742i + 0.237j) with
  // "= -0.5i - 0.5j" (Example 4.1's numbers); its own terms give -0.371i - 1.157j, as
  // the finite differences of CB do (sample comments): that is asserted — to the
  // seed's terms' rounding in x, and against CB'' (finite differences) along link 3.
  CHECK_PRINTED(s.at("relative_acceleration")[0].get<double>(), "-0.371");
  const Model model = kinema::load_model(sample("example_4_2_joints.toml"));
  const double h = 1e-3, omega1 = 4.712;
  const MotionTable t = kinema::solve_motion(model, {M_PI / 4 - h, M_PI / 4, M_PI / 4 + h});
  const double cb_second = (coordinate_value(model, t, 2, "CB", 0) - 2 * coordinate_value(model, t, 1, "CB", 0) +
                            coordinate_value(model, t, 0, "CB", 0)) / (h * h) * omega1 * omega1;
  const double phi3 = coordinate_value(model, t, 1, "phi3", 0);
  CHECK(s.at("relative_acceleration")[0].get<double>() == doctest::Approx(cb_second * std::cos(phi3)).epsilon(1e-5));
  CHECK(s.at("relative_acceleration")[1].get<double>() == doctest::Approx(cb_second * std::sin(phi3)).epsilon(1e-5));
  CHECK(s.at("relative_acceleration")[1].get<double>() == doctest::Approx(-1.157).epsilon(0.002));
  // omega21 = omega2 - omega1 (the block 2 turns with link 3).
  CHECK_PRINTED(e42.at("blocks").at("2").at("rate").get<double>() - 4.712, "-2.905");
  // A slider on a fixed guide has no Coriolis term.
  CHECK(e42.at("sliders").at("E5").at("coriolis")[0].get<double>() == 0);
}

TEST_CASE("linkages/linkage_loops: the guide's point under each slider and the blocks' relative turnings are outputs") {
  // Example 4.1: v_B1 = -0.804i + 0.804j m/s, a_B1 = -2.528i - 2.528j m/s^2 (B on the crank 1),
  // omega23 = -0.762 rad/s, alpha23 = 2.252 rad/s^2 (block 2 relative to link 3 at B).
  const nlohmann::json e41 = kinema_test::eval_json("example_4_1_joints.toml").at("results").at(0);
  const nlohmann::json& b1 = e41.at("guide_points").at("B1");
  CHECK(b1.at("slider") == "B2");
  CHECK(b1.at("link") == "1");
  CHECK_PRINTED(b1.at("velocity")[0].get<double>(), "-0.804");
  CHECK_PRINTED(b1.at("velocity")[1].get<double>(), "0.804");
  CHECK_PRINTED(b1.at("acceleration")[0].get<double>(), "-2.528");
  CHECK_PRINTED(b1.at("acceleration")[1].get<double>(), "-2.528");
  const nlohmann::json& w23 = e41.at("relative_turnings").at("omega23");
  CHECK(w23.at("links") == nlohmann::json::array({"2", "3"}));
  CHECK(w23.at("joint") == "B");
  CHECK(w23.at("second_rate_name") == "alpha23");
  CHECK_PRINTED(w23.at("rate").get<double>(), "-0.762");
  CHECK_PRINTED(w23.at("second_rate").get<double>(), "2.252");
  // Independently: the crank's point at B turns about A (the origin) at omega1 = 3.141, alpha1 = 0.
  const double xb = e41.at("points").at("B").at("position")[0], yb = e41.at("points").at("B").at("position")[1];
  CHECK(b1.at("velocity")[0].get<double>() == doctest::Approx(-3.141 * yb).epsilon(1e-12));
  CHECK(b1.at("velocity")[1].get<double>() == doctest::Approx(3.141 * xb).epsilon(1e-12));
  CHECK(b1.at("acceleration")[0].get<double>() == doctest::Approx(-3.141 * 3.141 * xb).epsilon(1e-12));
  CHECK(b1.at("acceleration")[1].get<double>() == doctest::Approx(-3.141 * 3.141 * yb).epsilon(1e-12));

  // Example 4.2: v_B3 = -0.398i + 0.127j m/s, a_B3 = -0.456i - 0.649j m/s^2 (B on link 3),
  // omega21 = -2.905 rad/s (block 2 relative to the crank 1 at B).
  const nlohmann::json e42 = kinema_test::eval_json("example_4_2_joints.toml").at("results").at(0);
  const nlohmann::json& b3 = e42.at("guide_points").at("B3");
  CHECK_PRINTED(b3.at("velocity")[0].get<double>(), "-0.398");
  CHECK_PRINTED(b3.at("velocity")[1].get<double>(), "0.127");
  CHECK_PRINTED(b3.at("acceleration")[0].get<double>(), "-0.456");
  CHECK_PRINTED(b3.at("acceleration")[1].get<double>(), "-0.649");
  CHECK_PRINTED(e42.at("relative_turnings").at("omega21").at("rate").get<double>(), "-2.905");
  CHECK(e42.at("guide_points").size() == 1);  // E5's guide is ground: its point does not move
  // Link 3 turns about C (the origin): v = i w3 r_B, a = (i alpha3 - w3^2) r_B.
  const double w3 = e42.at("coordinates").at("phi3").at("rate"), a3 = e42.at("coordinates").at("phi3").at("second_rate");
  const std::complex<double> rb(e42.at("points").at("B").at("position")[0], e42.at("points").at("B").at("position")[1]);
  const std::complex<double> vb3 = std::complex<double>(0, w3) * rb, ab3 = std::complex<double>(-w3 * w3, a3) * rb;
  CHECK(b3.at("velocity")[0].get<double>() == doctest::Approx(vb3.real()).epsilon(1e-12));
  CHECK(b3.at("velocity")[1].get<double>() == doctest::Approx(vb3.imag()).epsilon(1e-12));
  CHECK(b3.at("acceleration")[0].get<double>() == doctest::Approx(ab3.real()).epsilon(1e-12));
  CHECK(b3.at("acceleration")[1].get<double>() == doctest::Approx(ab3.imag()).epsilon(1e-12));

  // The same numbers in the table, CSV and npy columns.
  const auto table = kinema_test::run_kinema({"eval", kinema_test::sample("example_4_1_joints.toml")});
  CHECK(table.out.find("  B1      (-0.804584, 0.804584)") != std::string::npos);
  CHECK(table.out.find("omega23 = -0.761804 rad/s") != std::string::npos);
  const auto csv = kinema_test::run_kinema({"eval", kinema_test::sample("example_4_1_joints.toml"), "--format", "csv"});
  for (const char* column : {"B1_vx [m/s]", "B1_vy [m/s]", "B1_ax [m/s^2]", "B1_ay [m/s^2]", "omega23 [rad/s]",
                             "alpha23 [rad/s^2]"}) {
    CAPTURE(column);
    CHECK(csv.out.find(column) != std::string::npos);
  }
  const auto latex = kinema_test::run_kinema({"latex", kinema_test::sample("example_4_1_joints.toml"), "--fragment"});
  CHECK(latex.out.find("${B}_{\\mathrm{1}}$ & 1 & $(-0.80458,\\ 0.80458)$ & $(-2.5272,\\ -2.5272)$") != std::string::npos);
  CHECK(latex.out.find("$\\omega_{23} = -0.7618$ & $\\alpha_{23} = 2.2521$") != std::string::npos);
  const auto npy = kinema_test::run_kinema({"eval", kinema_test::sample("example_4_2_joints.toml"), "--format", "npy"});
  for (const char* field : {"'B3_vx'", "'B3_ay'", "'omega21'", "'alpha54'"}) {
    CAPTURE(field);
    CHECK(npy.out.find(field) != std::string::npos);
  }
}

TEST_CASE("linkages/linkage_loops: links that form no dyad (a triad) are named and solved by Newton on their loops") {
  // A ternary link X, Y, Z held by three binary links (from the crank, and two from
  // ground): no two of the unplaced links make a dyad. Lengths are the sketch's.
  const std::string triad = R"(title = "a triad"
[joints]
A = { ground = true, at = ["0 m", "0 m"] }
B = { at = ["1 m", "1 m"] }
X = { at = ["2 m", "2 m"] }
Y = { at = ["3 m", "1.5 m"] }
Z = { at = ["2.5 m", "3 m"] }
P = { ground = true, at = ["4 m", "0 m"] }
Q = { ground = true, at = ["1 m", "4 m"] }
[links]
2 = { joints = ["A", "B"] }
3 = { joints = ["B", "X"] }
4 = { joints = ["X", "Y", "Z"] }
5 = { joints = ["P", "Y"] }
6 = { joints = ["Q", "Z"] }
[driver]
link = "2"
value = "45 deg"
rate = "1 rad/s"
)";
  const Model model = model_of(triad);
  REQUIRE(model.system.plan);
  const auto& structure = model.system.plan->steps;
  REQUIRE(structure.size() == 2);
  CHECK(structure[1].kind == "group");
  CHECK(structure[1].links == std::vector<std::string>{"3", "4", "5", "6"});
  CHECK_FALSE(model.system.plan->closed_form);
  CHECK(model.kinematics.closed_form() == nullptr);
  std::ostringstream text;
  kinema::print_view(*kinema::find_printer(kinema::PrintKind::derivation, "text"), text, {model});
  CHECK(text.str().find("not a dyad: links 3, 4, 5, 6, solved together by Newton on their loops") != std::string::npos);
  // At the sketch's input the sketch is the solution; nearby, the loops close.
  const MotionTable t = kinema::solve_motion(model, {M_PI / 4, 50 * M_PI / 180});
  REQUIRE(t.status(0) == kinema::Status::ok);
  REQUIRE(t.status(1) == kinema::Status::ok);
  CHECK(coordinate_value(model, t, 0, "theta3", 0) == doctest::Approx(M_PI / 4));
  CHECK(t.loop_residual(1) < 1e-12);
}


TEST_CASE("linkages/linkage_loops: an assembly stated on a dyad's middle joint overrides the sketch's") {
  // The parallelogram of Problem 4.1 sketched as a parallelogram (C left of B-D), with
  // C stated right of B-D: the anti-parallelogram, the other sample's numbers.
  const std::string parallelogram = kinema_test::read_file(sample("problem_4_1_parallelogram.toml"));
  const std::string sketched_c = R"(C = { at = ["0.1246410 m", "0.02 m"] })";
  const auto stated = [&](const std::string& assembly) {
    return edited(sketched_c, R"(C = { at = ["0.1246410 m", "0.02 m"], assembly = ")" + assembly + R"(" })",
                  parallelogram);
  };
  const Model crossed = model_of(stated("right of B-D"));
  const Model anti = kinema::load_model(sample("problem_4_1_antiparallelogram.toml"));
  check_same_motion(crossed, anti, degrees(10, 170, 20));
  check_same_motion(crossed, anti, degrees(190, 350, 20));
  // The unknowns' guesses follow, so the loops kinema writes out are the crossed ones too.
  const Model written = kinema::make_model(
      kinema::read_mechanism_text(kinema_test::loops_file(kinema::read_mechanism_text(stated("right of B-D"), "s.toml")),
                                  "written.toml"));
  check_same_motion(written, anti, degrees(10, 170, 20));
  // The side the sketch already has changes nothing; derive says what was stated.
  const Model same = model_of(stated("left of B-D"));
  check_same_motion(same, kinema::load_model(sample("problem_4_1_parallelogram.toml")), degrees(10, 170, 40));
  std::ostringstream derivation;
  kinema::print_view(*kinema::find_printer(kinema::PrintKind::derivation, "text"), derivation, {crossed});
  CHECK(derivation.str().find("dyad 1, RRR: links 2, 3; joints B, C, D; assembly C right of B-D (stated in the file)") !=
        std::string::npos);

  SUBCASE("a side that both assemblies, or neither, are on") {
    for (const char* assembly : {"right of A-B", "left of A-B"}) {
      const std::string message = error_of(stated(assembly));
      CAPTURE(message);
      CHECK(message.find("lk.toml:") == 0);
      CHECK(message.find("assembly of the dyad puts C") != std::string::npos);
      CHECK(message.find("such as the dyad's outer joints B-D") != std::string::npos);
    }
  }
  SUBCASE("not a side, an unknown joint, one joint twice") {
    CHECK(error_of(stated("above B-D")).find("is not a side: write \"left of B-D\" or \"right of B-D\"") != std::string::npos);
    CHECK(error_of(stated("left of B-Z")).find("there is no joint \"Z\"") != std::string::npos);
    CHECK(error_of(stated("left of B-B")).find("a line needs two different joints") != std::string::npos);
  }
  SUBCASE("a joint that is not a dyad's middle joint") {
    const std::string message = error_of(edited(R"(B = { at = ["0.0346410 m", "0.02 m"] })",
                                                R"(B = { at = ["0.0346410 m", "0.02 m"], assembly = "left of A-D" })",
                                                parallelogram));
    CHECK(message.find("lk.toml:") == 0);
    CHECK(message.find("joint \"B\" states an assembly, but it is not the middle joint of a dyad (the middle joints: C)") !=
          std::string::npos);
  }
}
