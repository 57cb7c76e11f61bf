// The command solves each requested value once (issue 34): run in this process so that
// the engine's count of solved values can be read before and after.
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "engine/base/work_count.hpp"
#include "engine/numeric/sweep.hpp"

#include "cli/run.hpp"
#include "tests/test_support.hpp"

namespace {

// Values the command solved for these arguments (its exit status must be 0).
std::uint64_t values_solved_by(std::vector<std::string> arguments) {
  arguments.insert(arguments.begin(), "kinema");
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  const std::uint64_t before = kinema::values_solved_in_process();
  const int status = kinema_cli::run(static_cast<int>(argv.size()), argv.data());
  CHECK(status == 0);
  return kinema::values_solved_in_process() - before;
}

}  // namespace

TEST_CASE("kinema eval solves each value of an --angle list once, in every format") {
  const auto directory = kinema_test::scratch_directory() / "solve_once";
  std::filesystem::create_directories(directory);
  const std::string out = (directory / "out").string();
  for (const char* sample : {"four_bar.toml", "example_4_2_joints.toml", "robot_arm_seed000.toml"}) {
    for (const char* format : {"table", "csv", "json", "npy"}) {
      CAPTURE(sample);
      CAPTURE(format);
      const std::string file = kinema_test::sample(sample);
      // Whatever else a run solves (design figures over the turn), three more values in
      // the list are three more solves: one each, not one to check and one to print.
      const std::uint64_t three = values_solved_by({"eval", file, "--format", format, "-o", out, "--at", "0.1",
                                                    "--at", "0.2", "--at", "0.3"});
      const std::uint64_t six = values_solved_by({"eval", file, "--format", format, "-o", out, "--at", "0.1",
                                                  "--at", "0.2", "--at", "0.3", "--at", "0.4", "--at", "0.5",
                                                  "--at", "0.6"});
      CHECK(six - three == 3);
    }
  }
}

TEST_CASE("each command works out what its view shows once: design figures, dyads, drawings") {
  const auto directory = kinema_test::scratch_directory() / "analyse_once";
  std::filesystem::create_directories(directory);
  const std::string out = (directory / "out").string();
  const auto work_by = [&](kinema::Work work, const std::vector<std::string>& arguments) {
    const std::uint64_t before = kinema::work_done_in_process(work);
    values_solved_by(arguments);
    return kinema::work_done_in_process(work) - before;
  };
  const std::string four_bar = kinema_test::sample("four_bar.toml");
  const std::string joints = kinema_test::sample("example_4_2_joints.toml");
  // A four-bar's figures and its sliders' strokes: once each per command that shows them,
  // a table and a streamed sweep alike; none for a format that does not.
  CHECK(work_by(kinema::Work::design_figures, {"eval", four_bar, "-o", out}) == 2);
  CHECK(work_by(kinema::Work::design_figures, {"eval", four_bar, "--sweep", "0:90:1", "-q", "-o", out}) == 2);
  CHECK(work_by(kinema::Work::design_figures, {"eval", four_bar, "--format", "csv", "-o", out}) == 0);
  CHECK(work_by(kinema::Work::design_figures, {"latex", four_bar, "-o", out}) == 2);
  CHECK(work_by(kinema::Work::dyad_derivation, {"derive", joints, "--method", "relative-velocity", "-o", out}) == 1);
  CHECK(work_by(kinema::Work::dyad_derivation, {"latex", joints, "--method", "joint-coordinates", "-o", out}) == 1);
}
