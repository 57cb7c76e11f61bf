// kinema eval streams (issue 10): what it writes is the printer over the whole table
// byte for byte, with any number of formatting threads; a run that fails half-way
// leaves no file; a long run shows progress on a terminal and nowhere else.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "engine/run/view.hpp"
#include "engine/model.hpp"
#include "engine/printers/printer.hpp"
#include "readers/mechanism_file.hpp"

#include "tests/test_support.hpp"

namespace {

using kinema_test::run_kinema;
using kinema_test::run_shell;
using kinema_test::shell_quote;

// Over several 2048-row blocks; the slider input out past where the mechanism comes apart.
std::string sweep_for(const kinema::Model& model) {
  return model.system.input.dimension == kinema::Dimension::angle ? "-10:370:0.1" : "60:210:0.05";
}

}  // namespace

// The library test (tests/engine/run/results_stream_test.cpp) shows streamed ==
// whole table byte for byte in one process. Across processes the last bit of a number may
// differ: GiNaC orders terms by addresses, and the command line runs with address
// randomisation off (its own output is the same in every run) while this test does not.
// So here: the same rows, statuses and text, numbers equal to 1e-9; and the command
// line's output on one and on two threads byte for byte.
bool same_to_rounding(const std::string& a, const std::string& b) {
  auto split = [](const std::string& text) {
    std::vector<std::string> tokens;
    std::string token;
    for (char c : text) {
      if (std::string(",\n []{}:\"").find(c) != std::string::npos) {
        if (!token.empty()) tokens.push_back(token);
        tokens.push_back(std::string(1, c));
        token.clear();
      } else {
        token += c;
      }
    }
    if (!token.empty()) tokens.push_back(token);
    return tokens;
  };
  const auto x = split(a), y = split(b);
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] == y[i]) continue;
    char *end_x = nullptr, *end_y = nullptr;
    const double u = std::strtod(x[i].c_str(), &end_x), v = std::strtod(y[i].c_str(), &end_y);
    if (*end_x != '\0' || *end_y != '\0' || !(std::fabs(u - v) <= 1e-9 * (1 + std::fabs(u)))) return false;
  }
  return true;
}

TEST_CASE("kinema eval: streamed output is the printer over the whole table, on 1 and 2 threads the same bytes" * doctest::skip(kinema_test::kSanitized)) {
  const std::string directory = kinema_test::fresh_directory("streaming_bytes");
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const std::string sweep = sweep_for(model);
    const auto dimension = model.system.input.dimension;
    const double unit = dimension == kinema::Dimension::angle  ? M_PI / 180
                        : dimension == kinema::Dimension::time ? 1.0
                                                               : model.system.output.length_factor;
    const kinema::MotionTable whole = kinema::solve_motion(model, kinema::parse_sweep(sweep, unit).to_vector());
    REQUIRE(whole.size() > 3000);
    for (const std::string format : {"table", "csv", "json", "npy"}) {
      CAPTURE(format);
      kinema::PrintJob job{model, &whole};
      std::ostringstream expected;
      kinema::print_view(*kinema::find_printer(kinema::PrintKind::results, format), expected, job);
      std::string printed[2];
      for (int t = 0; t < 2; ++t) {
        const std::string path = directory + "/out." + format;
        const auto run = run_kinema({"eval", kinema_test::sample(sample), "--sweep", sweep, "--format", format,
                                     "--threads", t == 0 ? "1" : "2", "-o", path});
        CAPTURE(run.err);
        REQUIRE(run.exit_status == 0);
        printed[t] = kinema_test::read_file(path);
      }
      CHECK(printed[1] == printed[0]);
      if (format != "npy") CHECK(same_to_rounding(printed[0], expected.str()));
      else CHECK(printed[0].size() == expected.str().size());  // values: tests/cli/data_formats_test.cpp
    }
  }
}

TEST_CASE("kinema eval: a list whose third value cannot be assembled writes nothing, to a file or to stdout") {
  const std::string directory = kinema_test::fresh_directory("streaming_failed_list");
  const std::string path = directory + "/out.csv";
  const std::string file = kinema_test::sample("piston_driven_crank.toml");
  const std::vector<std::string> list = {"eval", file, "--format", "csv", "--angle", "170", "--angle", "180",
                                         "--angle", "400"};
  auto to_file = list;
  to_file.insert(to_file.end(), {"-o", path});
  const auto fresh = run_kinema(to_file);
  CAPTURE(fresh.err);
  CHECK(fresh.exit_status == 3);
  CHECK(fresh.err.find("x = 400 mm") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK(std::filesystem::is_empty(directory));  // no temporary either
  // A file already there stays as it was.
  std::ofstream(path) << "previous\n";
  CHECK(run_kinema(to_file).exit_status == 3);
  CHECK(kinema_test::read_file(path) == "previous\n");
  const auto to_stdout = run_kinema(list);
  CHECK(to_stdout.exit_status == 3);
  CHECK(to_stdout.out.empty());
  // The first two values alone are printed.
  const auto good = run_kinema({"eval", file, "--format", "csv", "--angle", "170", "--angle", "180"});
  CHECK(good.exit_status == 0);
  CHECK(std::count(good.out.begin(), good.out.end(), '\n') == 3);
}

TEST_CASE("kinema eval: a progress line on a terminal for a long run, none with --quiet or when stderr is not one" * doctest::skip(kinema_test::kSanitized)) {
  const std::string checker = std::string(KINEMA_SAMPLES_DIR) + "/../tests/tools/progress_on_terminal.py";
  const std::string run = shell_quote(KINEMA_EXE) + " eval " + shell_quote(kinema_test::sample("problem_4_4_six_bar.toml")) +
                          " --sweep 0:1800:0.0005 --format csv --threads 1 -o /dev/null";
  // Over a second of work on any machine (3.6 million rows of 49 numbers: 2 s here).
  const auto shown = run_shell("/usr/bin/python3 " + shell_quote(checker) + " " + run);
  CAPTURE(shown.err);
  REQUIRE(shown.exit_status == 0);
  CHECK(shown.out.rfind("0\n", 0) == 0);  // kinema's exit status
  CHECK(shown.out.find("of 3600001 values") != std::string::npos);
  CHECK(shown.out.find("values/s") != std::string::npos);
  CHECK(shown.out.find("s left") != std::string::npos);
  CHECK(shown.out.find("\\r\\x1b[K'") != std::string::npos);  // the line is cleared at the end

  const auto quiet = run_shell("/usr/bin/python3 " + shell_quote(checker) + " " + run + " --quiet");
  CHECK(quiet.out == "0\nb''\n");
  // Results scrolling on the same terminal: no progress line among them.
  const std::string on_terminal = shell_quote(KINEMA_EXE) + " eval " +
                                  shell_quote(kinema_test::sample("problem_4_4_six_bar.toml")) +
                                  " --sweep 0:360:0.002 --format csv --threads 1";  // over a second on a terminal
  const auto scrolling = run_shell("/usr/bin/python3 " + shell_quote(checker) + " --stdout-too " + on_terminal);
  CHECK(scrolling.out.rfind("0\n", 0) == 0);
  CHECK(scrolling.out.find(" False\n") != std::string::npos);  // over 100 MB of results, no progress line
  CHECK(scrolling.out.size() > 12);
  const auto piped = run_shell(run);  // stderr captured through a pipe
  CHECK(piped.exit_status == 0);
  CHECK(piped.err.empty());
}

TEST_CASE("kinema eval: a sweep beyond the list limit is refused only when mixed with --angle (a list)") {
  const auto mixed = run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--angle", "3", "--sweep", "0:360:0.00001"});
  CHECK(mixed.exit_status == 2);
  CHECK(mixed.err.find("more than 10000000 values") != std::string::npos);
  CHECK(mixed.err.find("--sweep alone") != std::string::npos);
  const auto huge = run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--sweep", "0:1e10:1"});
  CHECK(huge.exit_status == 2);
  CHECK(huge.err.find("more than 1000000000 values") != std::string::npos);
}
