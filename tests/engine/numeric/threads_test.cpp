// Multi-threaded sweeps give the serial results: same branch, same numbers.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "engine/model.hpp"
#include "tests/test_support.hpp"

TEST_CASE("batch (SIMD blocks), threads and both equal the scalar one-by-one run for every sample") {
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const auto& input = model.system.input;
    std::vector<double> inputs;
    const bool angle = input.dimension == kinema::Dimension::angle;
    for (int i = 0; i < 2000; ++i) {
      inputs.push_back(angle ? input.values.at(0) + 2 * M_PI * i / 2000.0 : 0.101 + 0.098 * i / 2000.0);
    }
    const auto serial = kinema::solve_motion(model, inputs, kinema_test::with_rates(input.rate_value, input.second_rate_value, 1, false));
    for (const auto& [threads, batch] : {std::pair{1u, true}, std::pair{3u, false}, std::pair{3u, true}}) {
    CAPTURE(threads);
    CAPTURE(batch);
    const auto parallel = kinema::solve_motion(model, inputs, kinema_test::with_rates(input.rate_value, input.second_rate_value, threads, batch));
    REQUIRE(serial.size() == parallel.size());
    CHECK(serial.batch_rows() == 0);
    // The SIMD path does the bulk of a fine sweep (not a fallback that never engages).
    if (batch) CHECK(parallel.batch_rows() >= serial.size() / 2);
    if (!batch) CHECK(parallel.batch_rows() == 0);
    int ok = 0;
    // Rounding noise is relative to the size of the rates (a zero second rate of a
    // parallelogram at 120 rpm comes out as 1e-9 on either path): tolerances on that scale.
    const double w = std::max(1.0, std::fabs(input.rate_value)), w2 = std::max(1.0, w * w + std::fabs(input.second_rate_value));
    const double l = model.system.length_scale;
    for (std::size_t i = 0; i < serial.size(); ++i) {
      CAPTURE(i);
      REQUIRE(serial[i].status == parallel[i].status);
      if (serial[i].status != kinema::Status::ok) continue;
      ++ok;
      // ... and grows with the condition of Phi_q near a toggle or change point; right next
      // to one (the parallelogram 0.06 deg from 180 deg) the rates are ill-conditioned
      // whichever path solves them, and only the positions are compared.
      if (serial[i].reciprocal_condition < 1e-2) {
        for (Eigen::Index j = 0; j < serial[i].q.size(); ++j) CHECK(std::fabs(parallel[i].q[j] - serial[i].q[j]) < 1e-9);
        continue;
      }
      const double e = 1e-9 / std::min(1.0, serial[i].reciprocal_condition);
      for (Eigen::Index j = 0; j < serial[i].q.size(); ++j) {
        CHECK(parallel[i].q[j] == doctest::Approx(serial[i].q[j]).epsilon(1e-12));
        CHECK(parallel[i].qd[j] == doctest::Approx(serial[i].qd[j]).epsilon(e).scale(w));
        CHECK(parallel[i].qdd[j] == doctest::Approx(serial[i].qdd[j]).epsilon(e).scale(w2));
      }
      for (std::size_t p = 0; p < serial[i].points.size(); ++p) {
        CHECK(parallel[i].points[p].acceleration[0] ==
              doctest::Approx(serial[i].points[p].acceleration[0]).epsilon(e).scale(l * w2));
        CHECK(parallel[i].points[p].velocity[1] == doctest::Approx(serial[i].points[p].velocity[1]).epsilon(e).scale(l * w));
      }
    }
    CHECK(ok > 100);
    }
  }
}

TEST_CASE("kinema eval --threads prints what the serial run prints, byte for byte") {
  // Threads format blocks of the one serial solve (tests/cli/streaming_test.cpp checks
  // every sample and format); the default is one thread per core.
  const auto serial = kinema_test::run_kinema({"eval", kinema_test::sample("problem_4_4_six_bar.toml"), "--sweep",
                                               "0:360:0.05", "--format", "csv", "--threads", "1"});
  REQUIRE(serial.exit_status == 0);
  CHECK(std::count(serial.out.begin(), serial.out.end(), '\n') == 7202);
  for (const char* threads : {"2", "7"}) {
    const auto parallel = kinema_test::run_kinema({"eval", kinema_test::sample("problem_4_4_six_bar.toml"), "--sweep",
                                                   "0:360:0.05", "--format", "csv", "--threads", threads});
    REQUIRE(parallel.exit_status == 0);
    CHECK(parallel.out == serial.out);
  }
  const auto by_default = kinema_test::run_kinema(
      {"eval", kinema_test::sample("problem_4_4_six_bar.toml"), "--sweep", "0:360:0.05", "--format", "csv"});
  CHECK(by_default.out == serial.out);
}
