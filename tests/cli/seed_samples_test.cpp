// Every number the seeds print that kinema reproduces, through the CLI, to
// the precision printed (one unit of the last digit or 0.1 %).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "tests/test_support.hpp"

using kinema_test::eval_json;
using nlohmann::json;

namespace {

const json& coordinate(const json& doc, const std::string& name) {
  return doc.at("results").at(0).at("coordinates").at(name);
}
const json& point(const json& doc, const std::string& name) {
  return doc.at("results").at(0).at("points").at(name);
}

}  // namespace

TEST_CASE("Example 4.1 (R-TRR, seed 002): omega3, alpha3, vB, aB") {
  const json doc = eval_json("example_4_1_r_trr.toml");
  REQUIRE(doc["results"][0]["status"] == "ok");
  CHECK_PRINTED(coordinate(doc, "phi3")["rate"].get<double>(), "3.903");
  CHECK_PRINTED(coordinate(doc, "phi3")["second_rate"].get<double>(), "-2.252");
  // phi3 = 58.633 deg in the seed comes from the rounded xB = yB = 0.256 m.
  CHECK_PRINTED(coordinate(doc, "phi3")["value"].get<double>(), "58.633");
  const json& b = point(doc, "B");
  CHECK_PRINTED(b["position"][0].get<double>(), "0.256");
  CHECK_PRINTED(b["position"][1].get<double>(), "0.256");
  CHECK_PRINTED(b["velocity"][0].get<double>(), "-0.999");
  CHECK_PRINTED(b["velocity"][1].get<double>(), "0.609");
  CHECK_PRINTED(b["speed"].get<double>(), "1.171");
  CHECK_PRINTED(b["acceleration"][0].get<double>(), "-1.802");
  // The seed prints -4.255 (1.6 units of its last digit off, from rounded intermediates);
  // finite differences of B's position give -4.2534 (see the sample).
  CHECK_PRINTED(b["acceleration"][1].get<double>(), "-4.253");
  CHECK_PRINTED(b["acceleration_magnitude"].get<double>(), "4.620");
  // Relative velocity of B2 along link 1: r_dot * (cos phi, sin phi) = -0.195i - 0.195j.
  const double r_dot = coordinate(doc, "r")["rate"].get<double>();
  CHECK_PRINTED(r_dot * std::cos(M_PI / 4), "-0.195");
  // Relative acceleration along link 1: r_ddot * (cos phi, sin phi) = -0.5i - 0.5j.
  CHECK_PRINTED(coordinate(doc, "r")["second_rate"].get<double>() * std::cos(M_PI / 4), "-0.5");
  // Coriolis 2 omega1 x v_rel = 1.226i - 1.226j.
  CHECK_PRINTED(-2 * 3.141 * r_dot * std::sin(M_PI / 4), "1.226");
  // omega23 = omega1 - omega3 = -0.762 rad/s.
  CHECK_PRINTED(3.141 - coordinate(doc, "phi3")["rate"].get<double>(), "-0.762");
}

TEST_CASE("Example 4.2 (R-RTR-RRT, seed 002): links 3 and 4, D and E") {
  const json doc = eval_json("example_4_2_r_rtr_rrt.toml");
  REQUIRE(doc["results"][0]["status"] == "ok");
  CHECK_PRINTED(coordinate(doc, "phi3")["rate"].get<double>(), "1.807");
  CHECK_PRINTED(coordinate(doc, "phi3")["second_rate"].get<double>(), "1.020");
  CHECK_PRINTED(coordinate(doc, "phi4")["rate"].get<double>(), "0.221");
  CHECK_PRINTED(coordinate(doc, "phi4")["second_rate"].get<double>(), "-1.105");
  CHECK_PRINTED(coordinate(doc, "phi3")["value"].get<double>(), "72.235");
  CHECK_PRINTED(coordinate(doc, "phi4")["value"].get<double>(), "20.923");
  CHECK_PRINTED(coordinate(doc, "xE")["value"].get<double>(), "0.164");
  CHECK_PRINTED(coordinate(doc, "xE")["rate"].get<double>(), "0.113");
  CHECK_PRINTED(coordinate(doc, "xE")["second_rate"].get<double>(), "0.217");
  const json& b = point(doc, "B");
  CHECK_PRINTED(b["position"][0].get<double>(), "0.070");
  CHECK_PRINTED(b["position"][1].get<double>(), "0.220");
  CHECK_PRINTED(b["velocity"][0].get<double>(), "-0.333");
  CHECK_PRINTED(b["velocity"][1].get<double>(), "0.333");
  CHECK_PRINTED(b["speed"].get<double>(), "0.471");
  CHECK_PRINTED(b["acceleration"][0].get<double>(), "-1.569");
  CHECK_PRINTED(b["acceleration"][1].get<double>(), "-1.569");
  CHECK_PRINTED(b["acceleration_magnitude"].get<double>(), "2.220");
  const json& d = point(doc, "D");
  CHECK_PRINTED(d["position"][0].get<double>(), "-0.023");
  CHECK_PRINTED(d["position"][1].get<double>(), "-0.071");
  CHECK_PRINTED(d["velocity"][0].get<double>(), "0.129");
  CHECK_PRINTED(d["velocity"][1].get<double>(), "-0.041");
  CHECK_PRINTED(d["speed"].get<double>(), "0.135");
  CHECK_PRINTED(d["acceleration"][0].get<double>(), "0.147");
  CHECK_PRINTED(d["acceleration"][1].get<double>(), "0.210");
  CHECK_PRINTED(d["acceleration_magnitude"].get<double>(), "0.256");
  const json& e = point(doc, "E");
  CHECK_PRINTED(e["velocity"][0].get<double>(), "0.113");
  CHECK_PRINTED(e["acceleration"][0].get<double>(), "0.217");
  // omega21 = omega2 - omega1 = -2.905 rad/s (links 2 and 3 turn together).
  CHECK_PRINTED(coordinate(doc, "phi3")["rate"].get<double>() - 4.712, "-2.905");
}

TEST_CASE("Problem 4.4 (R-RRR-RRT six-bar, seed 004): rates, joints and angles") {
  const json doc = eval_json("problem_4_4_six_bar.toml");
  REQUIRE(doc["results"][0]["status"] == "ok");
  CHECK_PRINTED(doc["results"][0]["input_rate"].get<double>(), "6.28319");
  CHECK_PRINTED(coordinate(doc, "phi2")["rate"].get<double>(), "-1.1307");
  CHECK_PRINTED(coordinate(doc, "phi3")["rate"].get<double>(), "-2.82169");
  CHECK_PRINTED(coordinate(doc, "phi4")["rate"].get<double>(), "0.58475");
  CHECK_PRINTED(coordinate(doc, "yF")["rate"].get<double>(), "1.64625");
  CHECK_PRINTED(coordinate(doc, "phi2")["second_rate"].get<double>(), "-22.33");
  CHECK_PRINTED(coordinate(doc, "phi3")["second_rate"].get<double>(), "-2.20443");
  CHECK_PRINTED(coordinate(doc, "phi4")["second_rate"].get<double>(), "-21.453");
  CHECK_PRINTED(coordinate(doc, "yF")["second_rate"].get<double>(), "3.29262");
  CHECK_PRINTED(coordinate(doc, "phi2")["value"].get<double>(), "-60.1903");
  CHECK_PRINTED(coordinate(doc, "phi3")["value"].get<double>(), "4.32878");
  CHECK_PRINTED(coordinate(doc, "phi4")["value"].get<double>(), "71.8329");
  struct Expected {
    const char* name;
    const char *x, *y, *vx, *vy, *ax, *ay;
  };
  const Expected joints[] = {
      {"B", "0.129904", "0.075", "-0.471239", "0.81621", "-5.1284", "-2.96088"},
      {"C", "-0.0689445", "0.422073", "-0.0788027", "1.04105", "2.87595", "1.03567"},
      {"E", "-0.298288", "0.404712", "-0.127788", "1.68819", "4.66371", "1.67947"},
      {"F", "-0.37", "0.186177", "0", "1.64625", "0", "3.29262"},
  };
  for (const Expected& j : joints) {
    CAPTURE(j.name);
    const json& p = point(doc, j.name);
    CHECK_PRINTED(p["position"][0].get<double>(), j.x);
    CHECK_PRINTED(p["position"][1].get<double>(), j.y);
    CHECK_PRINTED(p["velocity"][0].get<double>(), j.vx);
    CHECK_PRINTED(p["velocity"][1].get<double>(), j.vy);
    CHECK_PRINTED(p["acceleration"][0].get<double>(), j.ax);
    CHECK_PRINTED(p["acceleration"][1].get<double>(), j.ay);
  }
}

TEST_CASE("Problem 3.22 (six-bar with two sliders, seed 003): rates and vC in inches") {
  const json doc = eval_json("problem_3_22_six_bar_sliders.toml");
  REQUIRE(doc["results"][0]["status"] == "ok");
  CHECK(doc["units"]["velocity"] == "in/s");
  CHECK_PRINTED(coordinate(doc, "theta5")["value"].get<double>(), "83");
  CHECK_PRINTED(coordinate(doc, "theta3")["value"].get<double>(), "10");
  CHECK_PRINTED(coordinate(doc, "theta3")["rate"].get<double>(), "-4.26");
  // dtheta3/dtheta2 = 0.1015 (the seed's kinematic coefficient).
  CHECK_PRINTED(coordinate(doc, "theta3")["rate"].get<double>() / -42.0, "0.1015");
  // The seed prints +65.3 after a sign slip; finite differences give -65.3 (see the sample).
  CHECK_PRINTED(coordinate(doc, "r1")["rate"].get<double>(), "-65.3");
  CHECK_PRINTED(coordinate(doc, "r1")["rate"].get<double>() / -42.0, "1.556");
  CHECK_PRINTED(coordinate(doc, "theta5")["rate"].get<double>(), "-7.67");
  CHECK_PRINTED(coordinate(doc, "r6")["rate"].get<double>(), "22.25");
  const json& c = point(doc, "C");
  // The seed prints -60.89 (1.2 units of its last digit off: it rounds theta3 to 10 deg);
  // finite differences of C's position give -60.902 (see the sample).
  CHECK_PRINTED(c["velocity"][0].get<double>(), "-60.90");
  CHECK_PRINTED(c["velocity"][1].get<double>(), "29.73");
  CHECK_PRINTED(c["speed"].get<double>(), "67.76");
  // The seed's first loop gives B's speed 65.3 in/s, leftwards.
  CHECK_PRINTED(point(doc, "B")["velocity"][0].get<double>(), "-65.3");
}

TEST_CASE("every sample runs through the CLI in every format, with no NaN") {
  for (const char* name : {"four_bar.toml", "slider_crank.toml", "piston_driven_crank.toml",
                           "example_4_1_r_trr.toml", "example_4_2_r_rtr_rrt.toml",
                           "problem_4_4_six_bar.toml", "problem_3_22_six_bar_sliders.toml"}) {
    CAPTURE(name);
    const auto derive = kinema_test::run_kinema({"derive", kinema_test::sample(name)});
    CHECK(derive.exit_status == 0);
    CHECK(derive.out.find("Solved rates") != std::string::npos);
    const auto table = kinema_test::run_kinema({"eval", kinema_test::sample(name)});
    CHECK(table.exit_status == 0);
    CHECK(table.out.find("units:") != std::string::npos);
    const auto csv = kinema_test::run_kinema({"eval", kinema_test::sample(name), "--format", "csv"});
    CHECK(csv.exit_status == 0);
    CHECK(std::count(csv.out.begin(), csv.out.end(), '\n') == 2);  // header + one value
    const json doc = eval_json(name);
    CHECK(doc["results"][0]["status"] == "ok");
    for (const std::string& output : {table.out, csv.out}) {
      CHECK(output.find("nan") == std::string::npos);
      CHECK(output.find("inf") == std::string::npos);
    }
  }
}
