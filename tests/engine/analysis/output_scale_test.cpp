// engine/analysis/output_scale: SI to the output units the file asks for, the
// same for every printer; angles in degrees wrapped to (-180, 180].
#include <doctest/doctest.h>

#include <cmath>

#include "engine/model.hpp"
#include "engine/numeric/circuit.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/problem_scale.hpp"
#include "tests/engine/unit_support.hpp"
#include "tests/test_support.hpp"

using kinema::Dimension;
using kinema::OutputScale;

namespace {

OutputScale scale_of(const std::string& text) { return OutputScale(kinema_unit::system_from_text(text)); }

}  // namespace

TEST_CASE("engine/analysis/output_scale: angles in degrees, wrapped to (-180, 180 deg)") {
  const OutputScale scale = scale_of(kinema_test::four_bar_text() + "[output]\nlength = \"mm\"\n");
  const auto deg = [&](double degrees) { return scale.coordinate(Dimension::angle, degrees * M_PI / 180.0); };
  CHECK(deg(40) == doctest::Approx(40).epsilon(1e-14));
  CHECK(deg(190) == doctest::Approx(-170).epsilon(1e-14));
  CHECK(deg(-190) == doctest::Approx(170).epsilon(1e-14));
  CHECK(deg(725) == doctest::Approx(5).epsilon(1e-13));
  CHECK(deg(-359) == doctest::Approx(1).epsilon(1e-12));
  CHECK(std::fabs(deg(360)) < 1e-12);
  // The ends of the interval: +180 stays, -180 becomes +180, and so do odd half turns.
  CHECK(scale.coordinate(Dimension::angle, M_PI) == doctest::Approx(180).epsilon(1e-14));
  CHECK(scale.coordinate(Dimension::angle, -M_PI) == doctest::Approx(180).epsilon(1e-14));
  CHECK(scale.coordinate(Dimension::angle, 3 * M_PI) == doctest::Approx(180).epsilon(1e-14));
  CHECK(scale.coordinate(Dimension::angle, -3 * M_PI) == doctest::Approx(180).epsilon(1e-14));
  for (double radians = -20.0; radians <= 20.0; radians += 0.37) {
    const double wrapped = scale.coordinate(Dimension::angle, radians);
    CAPTURE(radians);
    CHECK(wrapped > -180.0);
    CHECK(wrapped <= 180.0);
    // Same direction as the angle itself.
    CHECK(std::cos(wrapped * M_PI / 180.0) == doctest::Approx(std::cos(radians)).epsilon(1e-12));
    CHECK(std::sin(wrapped * M_PI / 180.0) == doctest::Approx(std::sin(radians)).epsilon(1e-12));
  }
  // Unwrapped: continuous (inputs, curves).
  CHECK(scale.unwrapped(Dimension::angle, 3 * M_PI) == doctest::Approx(540).epsilon(1e-14));
  CHECK(scale.input(-7 * M_PI / 2) == doctest::Approx(-630).epsilon(1e-14));
  CHECK(scale.input_dimension == Dimension::angle);
  // Angular rates stay in rad/s (and rad/s^2).
  CHECK(scale.rate(Dimension::angle, 2.5) == 2.5);
  CHECK(scale.coordinate_unit(Dimension::angle) == "deg");
  CHECK(scale.rate_unit(Dimension::angle) == "rad/s");
  CHECK(scale.second_rate_unit(Dimension::angle) == "rad/s^2");
}

TEST_CASE("engine/analysis/output_scale: lengths in the file's unit, velocities per second") {
  const OutputScale mm = scale_of(kinema_test::four_bar_text() + "[output]\nlength = \"mm\"\n");
  CHECK(mm.length == doctest::Approx(0.001).epsilon(1e-15));
  CHECK(mm.length_unit == "mm");
  CHECK(mm.coordinate(Dimension::length, 0.05) == doctest::Approx(50).epsilon(1e-14));
  CHECK(mm.coordinate(Dimension::length, -0.5) == doctest::Approx(-500).epsilon(1e-14));  // lengths are not wrapped
  CHECK(mm.unwrapped(Dimension::length, 0.05) == doctest::Approx(50).epsilon(1e-14));
  CHECK(mm.rate(Dimension::length, 0.5) == doctest::Approx(500).epsilon(1e-14));
  CHECK(mm.coordinate_unit(Dimension::length) == "mm");
  CHECK(mm.rate_unit(Dimension::length) == "mm/s");
  CHECK(mm.second_rate_unit(Dimension::length) == "mm/s^2");

  const OutputScale inches = scale_of(kinema_test::four_bar_text() + "[output]\nlength = \"in\"\n");
  CHECK(inches.coordinate(Dimension::length, 0.0254) == doctest::Approx(1).epsilon(1e-14));
  CHECK(inches.rate_unit(Dimension::length) == "in/s");

  // No [output]: metres.
  const OutputScale metres = scale_of(kinema_test::four_bar_text());
  CHECK(metres.length == 1.0);
  CHECK(metres.coordinate(Dimension::length, 0.05) == 0.05);
  CHECK(metres.rate_unit(Dimension::length) == "m/s");

  // A slider input is a length: its values are not wrapped, in the output unit.
  const OutputScale piston(
      kinema_unit::system_from_text(kinema_test::read_file(kinema_test::sample("piston_driven_crank.toml"))));
  CHECK(piston.input_dimension == Dimension::length);
  CHECK(piston.input(0.17) == doctest::Approx(170).epsilon(1e-14));
  CHECK(piston.coordinate_unit(piston.input_dimension) == "mm");
}

// The tabular printers work out a block of rows column by column (result_rows) and size
// their rows by result_column_count: both must agree with result_columns and with
// result_values row by row, undefined rows (NaN) included.
TEST_CASE("engine/analysis/output_scale: result_rows of a block = result_values row by row, for every sample") {
  const auto same = [](double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; };
  const auto check_table = [&](const kinema::ConstraintSystem& system, const kinema::MotionTable& table) {
    const OutputScale scale(system);
    const std::size_t columns = kinema::result_column_count(system, table.is_circuit());
    REQUIRE(columns == kinema::result_columns(system, scale, table.is_circuit()).size());
    std::vector<double> block(columns * table.size(), -1.0), row(columns + 1, -1.0);
    kinema::result_rows(system, scale, table, 0, table.size(), block.data());
    for (std::size_t r = 0; r < table.size(); ++r) {
      kinema::result_values(system, scale, table, r, row.data());
      CHECK(row[columns] == -1.0);  // nothing written past the row
      for (std::size_t c = 0; c < columns; ++c) {
        if (!same(block[r * columns + c], row[c])) {
          CAPTURE(r);
          CAPTURE(c);
          CHECK(block[r * columns + c] == row[c]);
        }
      }
    }
    // A block from inside the table: the same rows.
    if (table.size() > 3) {
      std::vector<double> part(columns * 2);
      kinema::result_rows(system, scale, table, 1, 3, part.data());
      for (std::size_t k = 0; k < part.size(); ++k) CHECK(same(part[k], block[columns + k]));
    }
  };
  std::size_t undefined_rows = 0;
  for (const char* name : kinema_test::kSamples) {
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    std::vector<double> inputs;
    const double start = model.system.input.values.empty() ? 0.0 : model.system.input.values.front();
    for (int k = 0; k < 24; ++k) inputs.push_back(start + 0.3 * k);
    const kinema::MotionTable table = kinema::solve_motion(model, inputs);
    for (std::size_t r = 0; r < table.size(); ++r) undefined_rows += table.status(r) != kinema::Status::ok;
    check_table(model.system, table);
  }
  // A table along a circuit: its assembly signs come last.
  const kinema::Model rocker = kinema::load_model(kinema_test::sample("triple_rocker_circuit.toml"));
  kinema::CircuitSettings settings;
  settings.start = rocker.system.input.values.empty() ? 0.0 : rocker.system.input.values.front();
  settings.step = 0.05;
  settings.rate = 1;
  settings.max_rows = 10000;
  const kinema::Circuit circuit = kinema::solve_circuit(rocker.kinematics, settings);
  REQUIRE(circuit.table.is_circuit());
  check_table(rocker.system, circuit.table);
  CHECK(undefined_rows > 0);  // rows with NaN were compared too
}

TEST_CASE("engine/analysis/problem_scale: each value of a row is shown at its column's, its vector's and the problem's size") {
  for (const char* name : kinema_test::kSamples) {
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(name));
    const kinema::ConstraintSystem& system = model.system;
    const OutputScale scale(system);
    const kinema::ProblemScale problem(system);
    const std::vector<kinema::ResultColumn> columns = kinema::result_columns(system, scale);
    const kinema::RowScales row_scales(system, columns);
    const double start = system.input.values.empty() ? 0.0 : system.input.values.front();
    const kinema::MotionTable table = kinema::solve_motion(model, {start, start + 0.7, start + 1.9});
    for (std::size_t r = 0; r < table.size(); ++r) {
      if (table.status(r) != kinema::Status::ok) continue;
      std::vector<double> row(columns.size());
      kinema::result_values(system, scale, table, r, row.data());
      const std::vector<double> with = row_scales(row.data());
      REQUIRE(with.size() == columns.size());
      for (std::size_t k = 0; k < columns.size(); ++k) {
        CAPTURE(columns[k].name);
        CHECK(with[k] >= problem.of(columns[k]));
        if (k < kinema::kInputColumns) CHECK(with[k] == problem.of(columns[k]));  // the input's stand alone
        else CHECK(with[k] >= std::fabs(row[k]));
      }
      // Each member of a group (the places `at` of each entry) shown at its largest at least.
      const auto shown_together = [&](const std::vector<std::size_t>& at) {
        double largest = 0;
        for (std::size_t k : at) largest = std::max(largest, std::fabs(row[k]));
        for (std::size_t k : at) CHECK(with[k] >= largest);
        return largest;
      };
      const std::size_t n = system.unknowns.size();
      for (std::size_t order = 0; order < 3; ++order) {  // the table's value, rate and second rate columns
        std::vector<std::size_t> column;
        for (std::size_t i = 0; i < n; ++i) column.push_back(kinema::kInputColumns + 3 * i + order);
        shown_together(column);
      }
      // Points: a point's vector (with its magnitude), and each place over the points of its dimension.
      std::size_t at = kinema::kInputColumns + 3 * n;
      std::vector<std::size_t> begins, positions;
      for (const kinema::PointObservable& p : system.points) {
        const std::size_t d = p.components.size();
        begins.push_back(at);
        std::vector<std::size_t> position, velocity, acceleration;
        for (std::size_t c = 0; c < d; ++c) position.push_back(at + c);
        for (std::size_t c = 0; c <= d; ++c) velocity.push_back(at + d + c);
        for (std::size_t c = 0; c <= d; ++c) acceleration.push_back(at + 2 * d + 1 + c);
        shown_together(position);
        shown_together(velocity);
        shown_together(acceleration);
        if (d == 2) positions.insert(positions.end(), position.begin(), position.end());
        at += 3 * d + 2;
      }
      // A position is shown with positions only: the velocities' sizes do not enter.
      double extent = problem.of(Dimension::length, 0);
      for (std::size_t k : positions) extent = std::max(extent, std::fabs(row[k]));
      for (std::size_t k : positions) CHECK(with[k] <= extent);
      for (std::size_t place = 0; place < 8; ++place) {  // the planar table's columns x, y, v_x, v_y, |v|, a_x, a_y, |a|
        std::vector<std::size_t> column;
        for (std::size_t p = 0; p < system.points.size(); ++p)
          if (system.points[p].components.size() == 2) column.push_back(begins[p] + place);
        shown_together(column);
      }
      // A slider's relative velocity, relative acceleration and Coriolis term: vectors over the sliders.
      if (system.plan) {
        std::size_t v = kinema::linkage_columns_begin(system) + 3 * kinema::block_links(system).size();
        for (std::size_t part = 0; part < 3; ++part) {
          std::vector<std::size_t> column;
          for (std::size_t s = 0; s < system.plan->sliders.size(); ++s)
            for (std::size_t c = 0; c < 2; ++c) column.push_back(v + 6 * s + 2 * part + c);
          shown_together(column);
        }
      }
    }
  }
}
