// engine/run/results_stream: a run printed while it is solved, block by block and
// on several formatting threads, gives the bytes of the printer over the whole table
// that solve_motion() solves in one piece, for every format and sample, through singular
// and unassembled rows.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "engine/run/view.hpp"
#include "engine/model.hpp"
#include "engine/run/results_stream.hpp"
#include "engine/analysis/output_scale.hpp"
#include "tests/test_support.hpp"

namespace {

// Angles over a turn and a bit; the slider input out past where the piston-driven crank
// comes apart (singular and unassembled rows, rows resumed after a gap).
kinema::InputValues run_of(const kinema::Model& model) {
  return model.system.input.dimension == kinema::Dimension::angle
             ? kinema::InputValues::sweep(-10, 0.25, 1500, M_PI / 180)
             : kinema::InputValues::sweep(60, 0.1, 1500, 1e-3);
}

std::string streamed(const kinema::Model& model, const kinema::InputValues& inputs, const kinema::ResultsPrinter& printer,
                     unsigned threads, std::size_t block_rows, int precision = 0) {
  std::string text;
  kinema::StreamSettings settings;
  settings.printer = &printer;
  settings.threads = threads;
  settings.block_rows = block_rows;
  settings.precision = precision;
  settings.write = [&](std::string_view piece) { text += piece; };
  kinema::stream_results(model, inputs, {}, settings);
  return text;
}

}  // namespace

TEST_CASE("engine/run/results_stream: streamed output equals the printer over the whole table, byte for byte") {
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const kinema::InputValues inputs = run_of(model);
    const kinema::MotionTable whole = kinema::solve_motion(model, inputs.to_vector());
    std::size_t failures = 0, resumed = 0;
    for (std::size_t row = 0; row < whole.size(); ++row) {
      failures += whole.status(row) != kinema::Status::ok;
      resumed += whole.failure(row).kind == kinema::Failure::Kind::resumed_after_gap;
    }
    if (name == "piston_driven_crank.toml") {
      CHECK(failures > 100);
      CHECK(resumed > 0);
    }
    for (const std::string format : {"table", "csv", "json", "npy"}) {
      CAPTURE(format);
      const kinema::ResultsPrinter* printer = kinema::find_results_printer(format);
      REQUIRE(printer != nullptr);
      for (int precision : {0, 4}) {
        if (format == "npy" && precision) continue;
        kinema::PrintJob job{model, &whole};
        job.precision = precision;
        std::ostringstream expected;
        kinema::print_view(*printer, expected, job);
        CHECK(expected.str().size() > 1500 * 50);
        for (const auto& [threads, block_rows] : {std::pair{1u, 37u}, std::pair{1u, 2048u}, std::pair{3u, 1u},
                                                  std::pair{3u, 100u}, std::pair{2u, 2048u},
                                                  std::pair{2u, 0u}}) {  // 0: sized from the run
          // Under the sanitizers three of the six (one thread, many, sized from the run):
          // the release run checks all six at ten times the speed.
          if (kinema_test::kSanitized && !(block_rows == 37 || block_rows == 1 || block_rows == 0)) continue;
          CAPTURE(threads);
          CAPTURE(block_rows);
          CHECK(streamed(model, inputs, *printer, threads, block_rows, precision) == expected.str());
        }
      }
    }
  }
}

TEST_CASE("engine/run/results_stream: blocks sized by their time (Python's Ctrl-C) give the same bytes") {
  // A target of 1 us: blocks shrink to kMinBlockRows at once and grow back by doubling when
  // the clock reads a fast one; whatever the sizes, the printer's bytes over the whole table.
  const kinema::ResultsPrinter& npy = *kinema::find_results_printer("npy");
  for (const char* sample : {"piston_driven_crank.toml", "four_bar.toml"}) {
    CAPTURE(sample);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const kinema::InputValues inputs = run_of(model);
    std::ostringstream expected;
    const kinema::MotionTable whole = kinema::solve_motion(model, inputs.to_vector());
    kinema::print_view(npy, expected, kinema::PrintJob{model, &whole});
    for (const unsigned threads : {1u, 2u}) {
      CAPTURE(threads);
      std::string text;
      std::size_t blocks = 0;
      kinema::StreamSettings settings;
      settings.printer = &npy;
      settings.threads = threads;
      settings.block_rows = 512;
      settings.block_time = std::chrono::microseconds(1);
      settings.write = [&](std::string_view piece) { text += piece; };
      settings.progress = [&](std::size_t, std::size_t) { ++blocks; };
      kinema::stream_results(model, inputs, {}, settings);
      CHECK(text == expected.str());
      CHECK(blocks > inputs.size() / 512 + 2);  // smaller blocks than asked
    }
  }
  using std::chrono::microseconds;
  CHECK(kinema::resized_block_rows(1024, 1024, microseconds(400'000), microseconds(20'000)) == 51);
  CHECK(kinema::resized_block_rows(20, 1024, std::chrono::seconds(10), microseconds(20'000)) == kinema::kMinBlockRows);
  CHECK(kinema::resized_block_rows(51, 1024, microseconds(1'000), microseconds(20'000)) == 102);
  CHECK(kinema::resized_block_rows(800, 1024, microseconds(1'000), microseconds(20'000)) == 1024);
  CHECK(kinema::resized_block_rows(800, 1024, microseconds(10'000), microseconds(20'000)) == 800);
}

TEST_CASE("engine/run/results_stream: the summary, failures in order, progress, and a write error stops the run") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("piston_driven_crank.toml"));
  const kinema::InputValues inputs = run_of(model);
  const kinema::MotionTable whole = kinema::solve_motion(model, inputs.to_vector());
  std::vector<double> failed;
  std::size_t last_done = 0, reports = 0;
  kinema::StreamSettings settings;  // no printer: solve only
  settings.block_rows = 64;
  settings.on_failure = [&](double input, kinema::Status, const kinema::Failure&) { failed.push_back(input); };
  settings.progress = [&](std::size_t done, std::size_t total) {
    CHECK(done > last_done);
    CHECK(total == inputs.size());
    last_done = done;
    ++reports;
  };
  const kinema::RunSummary summary = kinema::stream_results(model, inputs, {}, settings);
  std::vector<double> expected;
  for (std::size_t row = 0; row < whole.size(); ++row)
    if (whole.status(row) != kinema::Status::ok) expected.push_back(whole.input(row));
  CHECK(failed == expected);
  CHECK(summary.values == inputs.size());
  CHECK(summary.failures == expected.size());
  REQUIRE(summary.first_failure.has_value());
  CHECK(summary.first_failure->input == expected.front());
  CHECK(last_done == inputs.size());
  CHECK(reports >= inputs.size() / 64);

  // A writer that fails half-way (a full disk) stops the run with its exception, on
  // one thread and on several.
  for (unsigned threads : {1u, 2u, 3u}) {  // 2 on two cores or more: threads that wait by spinning
    CAPTURE(threads);
    std::size_t pieces = 0;
    kinema::StreamSettings failing;
    failing.printer = kinema::find_results_printer("csv");
    failing.threads = threads;
    failing.block_rows = 50;
    failing.write = [&](std::string_view) {
      if (++pieces == 5) throw std::runtime_error("disk full");
    };
    CHECK_THROWS_WITH(kinema::stream_results(model, inputs, {}, failing), "disk full");
    CHECK(pieces == 5);
  }
}

// Two loads of one file in one process may order GiNaC's terms differently (its symbols'
// hashes come from their serial numbers), so the numbers are compared within rounding.
TEST_CASE("engine/run/results_stream: a model derived for evaluation only gives the numbers of a full one") {
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model full = kinema::load_model(kinema_test::sample(sample));
    const kinema::Model evaluation = kinema::load_model(kinema_test::sample(sample), kinema::DerivationScope::evaluation);
    const kinema::InputValues inputs = run_of(full);
    const kinema::MotionTable a = kinema::solve_motion(full, inputs.to_vector());
    const kinema::MotionTable b = kinema::solve_motion(evaluation, inputs.to_vector());
    REQUIRE(a.size() == b.size());
    const kinema::OutputScale scale(full.system);
    std::vector<double> x(kinema::result_columns(full.system, scale).size()), y(x.size());
    std::size_t compared = 0;
    for (std::size_t row = 0; row < a.size(); ++row) {
      REQUIRE(a.status(row) == b.status(row));
      kinema::result_values(full.system, scale, a, row, x.data());
      kinema::result_values(evaluation.system, scale, b, row, y.data());
      for (std::size_t k = 0; k < x.size(); ++k) {
        if (std::isnan(x[k])) {
          CHECK(std::isnan(y[k]));
          continue;
        }
        if (std::fabs(x[k] - y[k]) > 1e-9 * (1 + std::fabs(x[k]))) {
          CAPTURE(row);
          CAPTURE(k);
          CHECK(y[k] == doctest::Approx(x[k]).epsilon(1e-9));
        }
        ++compared;
      }
    }
    CHECK(compared > 1000);
    for (const std::string format : {"table", "csv", "json", "npy"}) {  // every printer takes it
      CAPTURE(format);
      CHECK(streamed(evaluation, inputs, *kinema::find_results_printer(format), 2, 512).size() > 1500 * 50);
    }
  }
}
