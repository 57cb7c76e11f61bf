// Multi-threaded sweeps give the serial results: same branch, same numbers.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

#include <kinema/engine/model.hpp>
#include "test_support.hpp"

TEST_CASE("batch (SIMD blocks), threads and both equal the scalar one-by-one run for every sample") {
  for (const char* sample : {"four_bar.toml", "slider_crank.toml", "piston_driven_crank.toml",
                             "example_4_1_r_trr.toml", "example_4_2_r_rtr_rrt.toml",
                             "problem_4_4_six_bar.toml", "problem_3_22_six_bar_sliders.toml"}) {
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const auto& input = model.system.input;
    std::vector<double> inputs;
    const bool angle = input.dimension == kinema::Dimension::angle;
    for (int i = 0; i < 2000; ++i) {
      inputs.push_back(angle ? input.values.at(0) + 2 * M_PI * i / 2000.0 : 0.101 + 0.098 * i / 2000.0);
    }
    const auto serial = kinema::analyse(model, inputs, kinema_test::with_rates(input.rate_value, input.second_rate_value, 1, false));
    for (const auto& [threads, batch] : {std::pair{1u, true}, std::pair{3u, false}, std::pair{3u, true}}) {
    CAPTURE(threads);
    CAPTURE(batch);
    const auto parallel = kinema::analyse(model, inputs, kinema_test::with_rates(input.rate_value, input.second_rate_value, threads, batch));
    REQUIRE(serial.size() == parallel.size());
    CHECK(serial.batch_rows() == 0);
    // The SIMD path does the bulk of a fine sweep (not a fallback that never engages).
    if (batch) CHECK(parallel.batch_rows() >= serial.size() / 2);
    if (!batch) CHECK(parallel.batch_rows() == 0);
    int ok = 0;
    for (std::size_t i = 0; i < serial.size(); ++i) {
      CAPTURE(i);
      REQUIRE(serial[i].status == parallel[i].status);
      if (serial[i].status != kinema::Status::ok) continue;
      ++ok;
      for (Eigen::Index j = 0; j < serial[i].q.size(); ++j) {
        CHECK(parallel[i].q[j] == doctest::Approx(serial[i].q[j]).epsilon(1e-12));
        CHECK(parallel[i].qd[j] == doctest::Approx(serial[i].qd[j]).epsilon(1e-9));
        CHECK(parallel[i].qdd[j] == doctest::Approx(serial[i].qdd[j]).epsilon(1e-9));
      }
      for (std::size_t p = 0; p < serial[i].points.size(); ++p) {
        CHECK(parallel[i].points[p].acceleration[0] == doctest::Approx(serial[i].points[p].acceleration[0]).epsilon(1e-9));
        CHECK(parallel[i].points[p].velocity[1] == doctest::Approx(serial[i].points[p].velocity[1]).epsilon(1e-9));
      }
    }
    CHECK(ok > 100);
    }
  }
}

TEST_CASE("kinema eval --threads prints what the serial run prints") {
  const auto serial = kinema_test::run_kinema(
      {"eval", kinema_test::sample("problem_4_4_six_bar.toml"), "--sweep", "0:360:0.25", "--format", "csv"});
  const auto parallel = kinema_test::run_kinema({"eval", kinema_test::sample("problem_4_4_six_bar.toml"), "--sweep",
                                                 "0:360:0.25", "--format", "csv", "--threads", "2"});
  REQUIRE(serial.exit_status == 0);
  REQUIRE(parallel.exit_status == 0);
  // Same rows and statuses; numbers equal to rounding (chunk starts are reached by
  // a different path, so the last printed digit may differ).
  std::istringstream a(serial.out), b(parallel.out);
  std::string cell_a, cell_b;
  std::size_t cells = 0;
  auto next = [](std::istringstream& in, std::string& cell) {
    cell.clear();
    char c;
    while (in.get(c) && c != ',' && c != '\n') cell += c;
    return static_cast<bool>(in) || !cell.empty();
  };
  while (next(a, cell_a)) {
    REQUIRE(next(b, cell_b));
    ++cells;
    char* end_a = nullptr;
    const double x = std::strtod(cell_a.c_str(), &end_a);
    if (cell_a.empty() || *end_a != '\0') {
      CHECK(cell_a == cell_b);
      continue;
    }
    CHECK(std::fabs(x - std::stod(cell_b)) <= 1e-9 * (1 + std::fabs(x)));
  }
  CHECK_FALSE(next(b, cell_b));
  CHECK(cells > 1000);
}
