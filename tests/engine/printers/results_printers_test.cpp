// engine/printers (results): the table, CSV and JSON printers, found by name
// and run on a model and a MotionTable with an ok, a singular and an
// unassembled row. The numbers printed are the table's, in output units.
#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include <sstream>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/printers/printer.hpp"
#include "engine/base/number_format.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::MotionState;
using kinema::MotionTable;
using kinema::PrintKind;
using kinema::Status;
using kinema_unit::kDeg;

namespace {

std::string print(const char* name, const kinema::Model& model, const MotionTable& values) {
  const kinema::Printer* printer = kinema::find_printer(PrintKind::results, name);
  REQUIRE(printer != nullptr);
  std::ostringstream out;
  kinema::print_view(*printer, out, kinema::PrintJob{model, &values});
  return out.str();
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator && separator == ',') parts.push_back("");
  return parts;
}

// Equal to a relative 1e-12 (the JSON holds the doubles themselves), however small.
bool close(double a, double b) { return a == b || std::fabs(a - b) <= 1e-12 * std::max(std::fabs(a), std::fabs(b)); }

double wrapped_degrees(double radians) {
  double d = std::remainder(radians / kDeg, 360.0);
  return d <= -180 ? d + 360 : d;
}

// The piston-driven crank (lengths in mm) at 170 mm (ok), at its dead centre 200 mm
// (singular) and at 250 mm (beyond reach: unassembled).
struct PistonRun {
  kinema::Model model = kinema::load_model(kinema_test::sample("piston_driven_crank.toml"));
  MotionTable table{{0.17, 0.2, 0.25}, 2, {2, 2}, -2.0, 5.0};
  PistonRun() {
    table.set(0, kinema::solve_motion(model, {0.17})[0]);
    kinema::Workspace workspace(model);
    table.set(1, workspace.motion(0.2, -2.0, 5.0, Eigen::VectorXd::Zero(2)));
    table.set(2, kinema::solve_motion(model, {0.25})[0]);
  }
};

}  // namespace

TEST_CASE("engine/printers/results: the run the printers are given") {
  const PistonRun run;
  REQUIRE(run.table.status(0) == Status::ok);
  REQUIRE(run.table.status(1) == Status::singular);
  REQUIRE(run.table.status(2) == Status::unassembled);
  CHECK(run.table.failure(2).kind == kinema::Failure::Kind::group_open);
}

TEST_CASE("engine/printers/results: csv: header with units, one row per value, empty cells where undefined") {
  const PistonRun run;
  const std::string csv = print("csv", run.model, run.table);
  const std::vector<std::string> lines = split(csv, '\n');
  REQUIRE(lines.size() == 1 + 3);
  CHECK(lines[0] ==
        "x [mm],x_dot [mm/s],x_ddot [mm/s^2],status,"
        "theta2 [deg],omega2 [rad/s],alpha2 [rad/s^2],theta3 [deg],omega3 [rad/s],alpha3 [rad/s^2],"
        "A_x [mm],A_y [mm],A_vx [mm/s],A_vy [mm/s],A_speed [mm/s],A_ax [mm/s^2],A_ay [mm/s^2],A_acceleration [mm/s^2],"
        "B_x [mm],B_y [mm],B_vx [mm/s],B_vy [mm/s],B_speed [mm/s],B_ax [mm/s^2],B_ay [mm/s^2],B_acceleration [mm/s^2],"
        "note");
  const std::size_t columns = split(lines[0], ',').size();
  REQUIRE(columns == 27);

  // ok: every cell a number equal to the table's value in output units (12 significant digits).
  const std::vector<std::string> ok = split(lines[1], ',');
  REQUIRE(ok.size() == columns);
  CHECK(ok[3] == "ok");
  const MotionState s = run.table[0];
  const auto approx = [](double value) { return doctest::Approx(value).epsilon(1e-11); };
  CHECK(std::stod(ok[0]) == approx(170));
  CHECK(std::stod(ok[1]) == approx(-2000));
  CHECK(std::stod(ok[2]) == approx(5000));
  for (std::size_t i = 0; i < 2; ++i) {
    CAPTURE(i);
    CHECK(std::stod(ok[4 + 3 * i]) == approx(wrapped_degrees(s.q[i])));
    CHECK(std::stod(ok[5 + 3 * i]) == approx(s.qd[i]));   // rad/s as computed
    CHECK(std::stod(ok[6 + 3 * i]) == approx(s.qdd[i]));
  }
  for (std::size_t p = 0; p < 2; ++p) {
    CAPTURE(p);
    const kinema::PointMotion& m = s.points[p];
    const std::size_t at = 10 + 8 * p;
    CHECK(std::stod(ok[at + 0]) == approx(m.position[0] / 0.001));
    CHECK(std::stod(ok[at + 1]) == approx(m.position[1] / 0.001));
    CHECK(std::stod(ok[at + 2]) == approx(m.velocity[0] / 0.001));
    CHECK(std::stod(ok[at + 3]) == approx(m.velocity[1] / 0.001));
    CHECK(std::stod(ok[at + 4]) == approx(m.speed() / 0.001));
    CHECK(std::stod(ok[at + 5]) == approx(m.acceleration[0] / 0.001));
    CHECK(std::stod(ok[at + 6]) == approx(m.acceleration[1] / 0.001));
    CHECK(std::stod(ok[at + 7]) == approx(m.acceleration_magnitude() / 0.001));
  }
  // B is the piston pin: at x, on the axis, moving at the input's rate.
  CHECK(std::stod(ok[18]) == approx(170));
  CHECK(std::stod(ok[20]) == approx(-2000));

  // singular: the position, no rates, no points.
  const std::vector<std::string> singular = split(lines[2], ',');
  REQUIRE(singular.size() == columns);
  CHECK(std::stod(singular[0]) == approx(200));
  CHECK(singular[3] == "singular");
  CHECK_FALSE(singular[4].empty());
  CHECK_FALSE(singular[7].empty());
  for (std::size_t c : {5, 6, 8, 9}) CHECK(singular[c].empty());
  for (std::size_t c = 10; c < columns; ++c) CHECK(singular[c].empty());
  CHECK(std::fabs(std::stod(singular[4])) < 1e-3);  // crank along the axis

  // unassembled: nothing but the input and the status.
  const std::vector<std::string> open = split(lines[3], ',');
  REQUIRE(open.size() == columns);
  CHECK(std::stod(open[0]) == approx(250));
  CHECK(open[3] == "unassembled");
  for (std::size_t c = 4; c < columns; ++c) CHECK(open[c].empty());
  CHECK(csv.find("nan") == std::string::npos);
}

TEST_CASE("engine/printers/results: json: the documented keys and the table's numbers in output units") {
  const PistonRun run;
  const nlohmann::json doc = nlohmann::json::parse(print("json", run.model, run.table));
  CHECK(doc["title"] == run.model.system.title);
  CHECK(doc["units"] == nlohmann::json({{"angle", "deg"},
                                        {"angular_rate", "rad/s"},
                                        {"angular_second_rate", "rad/s^2"},
                                        {"length", "mm"},
                                        {"velocity", "mm/s"},
                                        {"acceleration", "mm/s^2"}}));
  CHECK(doc["input"] ==
        nlohmann::json({{"name", "x"}, {"kind", "length"}, {"rate_name", "x_dot"}, {"second_rate_name", "x_ddot"}}));
  REQUIRE(doc["coordinates"].size() == 2);
  CHECK(doc["coordinates"][0] == nlohmann::json({{"name", "theta2"},
                                                 {"kind", "angle"},
                                                 {"rate_name", "omega2"},
                                                 {"second_rate_name", "alpha2"}}));
  CHECK(doc["coordinates"][1]["name"] == "theta3");
  CHECK(doc["points"] == nlohmann::json({"A", "B"}));
  REQUIRE(doc["results"].size() == 3);

  const nlohmann::json& ok = doc["results"][0];
  const MotionState s = run.table[0];
  CHECK(close(ok["input"].get<double>(), 170));
  CHECK(close(ok["input_rate"].get<double>(), -2000));
  CHECK(close(ok["input_second_rate"].get<double>(), 5000));
  CHECK(ok["status"] == "ok");
  CHECK_FALSE(ok.contains("message"));
  CHECK(close(ok["coordinates"]["theta2"]["value"].get<double>(), wrapped_degrees(s.q[0])));
  CHECK(close(ok["coordinates"]["theta2"]["rate"].get<double>(), s.qd[0]));
  CHECK(close(ok["coordinates"]["theta3"]["second_rate"].get<double>(), s.qdd[1]));
  CHECK(close(ok["loop_residual"].get<double>(), s.loop_residual / 0.001));
  const nlohmann::json& a = ok["points"]["A"];
  const kinema::PointMotion& A = s.points[0];
  for (std::size_t c = 0; c < 2; ++c) {
    CHECK(close(a["position"][c].get<double>(), A.position[c] / 0.001));
    CHECK(close(a["velocity"][c].get<double>(), A.velocity[c] / 0.001));
    CHECK(close(a["acceleration"][c].get<double>(), A.acceleration[c] / 0.001));
  }
  CHECK(close(a["speed"].get<double>(), A.speed() / 0.001));
  CHECK(close(a["acceleration_magnitude"].get<double>(), A.acceleration_magnitude() / 0.001));
  // A is on the crank circle of radius a = 50 mm.
  CHECK(std::hypot(a["position"][0].get<double>(), a["position"][1].get<double>()) == doctest::Approx(50).epsilon(1e-12));

  const nlohmann::json& singular = doc["results"][1];
  CHECK(singular["status"] == "singular");
  CHECK(singular["message"].get<std::string>().find("singular position at x = 200 mm") == 0);
  CHECK(singular["coordinates"]["theta2"]["value"].is_number());
  CHECK(singular["coordinates"]["theta2"]["rate"].is_null());
  CHECK(singular["coordinates"]["theta3"]["second_rate"].is_null());
  CHECK(singular["points"].empty());
  CHECK(singular.contains("loop_residual"));

  const nlohmann::json& open = doc["results"][2];
  CHECK(open["status"] == "unassembled");
  CHECK(open["message"].get<std::string>().find("loop \"OAB\"") != std::string::npos);
  CHECK(open["message"].get<std::string>().find("x = 250 mm") != std::string::npos);
  CHECK(open["coordinates"].empty());
  CHECK(open["points"].empty());
  CHECK_FALSE(open.contains("loop_residual"));
}

TEST_CASE("engine/printers/results: table: one block per value, the numbers as format_significant prints them") {
  const PistonRun run;
  const std::string text = print("table", run.model, run.table);
  CAPTURE(text);
  using kinema::format_significant;
  CHECK(text.find(run.model.system.title + "\n") == 0);
  CHECK(text.find("lengths mm, velocities mm/s, accelerations mm/s^2") != std::string::npos);
  CHECK(text.find("x = 170 mm   x_dot = -2000 mm/s   x_ddot = 5000 mm/s^2\n") != std::string::npos);
  const MotionState s = run.table[0];
  CHECK(text.find("  theta2      " + format_significant(wrapped_degrees(s.q[0])) + " deg") != std::string::npos);
  CHECK(text.find("omega3 = " + format_significant(s.qd[1]) + " rad/s") != std::string::npos);
  CHECK(text.find("alpha2 = " + format_significant(s.qdd[0]) + " rad/s^2") != std::string::npos);
  CHECK(text.find("  point   x           y           vx") != std::string::npos);
  CHECK(text.find("  A       " + format_significant(s.points[0].position[0] / 0.001)) != std::string::npos);
  // The singular value: its sentence, its position, no rates.
  CHECK(text.find("x = 200 mm") != std::string::npos);
  CHECK(text.find("  SINGULAR: singular position at x = 200 mm") != std::string::npos);
  CHECK(text.find("undefined (singular)") != std::string::npos);
  // The unassembled value: only its sentence.
  CHECK(text.find("  not assembled: loop \"OAB\"") != std::string::npos);
  // Three blocks, one point table (for the ok value only).
  std::size_t blocks = 0, point_tables = 0;
  for (std::size_t at = text.find("x_dot = "); at != std::string::npos; at = text.find("x_dot = ", at + 1)) ++blocks;
  for (std::size_t at = text.find("  point "); at != std::string::npos; at = text.find("  point ", at + 1)) ++point_tables;
  CHECK(blocks == 3);
  CHECK(point_tables == 1);
}

TEST_CASE("engine/printers/results: an angle input is printed unwrapped, coordinates wrapped") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const MotionTable table = kinema::solve_motion(model, {40 * kDeg, 400 * kDeg});
  REQUIRE(table.status(1) == Status::ok);
  const std::vector<std::string> lines = split(print("csv", model, table), '\n');
  REQUIRE(lines.size() == 3);
  CHECK(lines[0].find("theta2 [deg],omega2 [rad/s],alpha2 [rad/s^2],status,theta3 [deg]") == 0);
  CHECK(lines[0].find(",P_vx [mm/s],") != std::string::npos);
  const std::vector<std::string> second = split(lines[2], ',');
  CHECK(std::stod(second[0]) == doctest::Approx(400));
  CHECK(std::stod(second[4]) == doctest::Approx(wrapped_degrees(table.q(1)[0])).epsilon(1e-11));
  const nlohmann::json doc = nlohmann::json::parse(print("json", model, table));
  CHECK(doc["results"][1]["input"].get<double>() == doctest::Approx(400));
  const double theta4 = doc["results"][1]["coordinates"]["theta4"]["value"].get<double>();
  CHECK(theta4 > -180);
  CHECK(theta4 <= 180);
  CHECK(theta4 == doctest::Approx(wrapped_degrees(kinema_unit::FourBar().theta4(400 * kDeg))).epsilon(1e-9));
}

// Issue 9, finding 16: a row reached after a gap says so in the CSV too (its last column).
TEST_CASE("engine/printers/results: csv: a row resumed after a gap carries the note") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("piston_driven_crank.toml"));
  const MotionTable table = kinema::solve_motion(model, {0.17, 0.25, 0.18});
  REQUIRE(table.status(1) == Status::unassembled);
  REQUIRE(table.failure(2).kind == kinema::Failure::Kind::resumed_after_gap);
  const std::vector<std::string> lines = split(print("csv", model, table), '\n');
  REQUIRE(lines.size() == 4);
  for (std::size_t row = 1; row <= 3; ++row) {
    CAPTURE(row);
    const std::vector<std::string> cells = split(lines[row], ',');
    REQUIRE(cells.size() == 27);
    CHECK(cells.back() == (row == 3 ? "resumed_after_gap" : ""));
  }
}
