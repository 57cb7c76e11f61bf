// Helpers shared by the tests: running the kinema CLI, reading its JSON,
// and comparing with numbers as the seeds print them.
#pragma once

#include <nlohmann/json.hpp>

#include "engine/model.hpp"
#include <filesystem>
#include <string>
#include <vector>

namespace kinema_test {

struct CommandResult {
  int exit_status = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
  long peak_kilobytes = 0;  ///< run_kinema_bounded: the largest resident size of a child so far
};

/// Runs the kinema executable with the arguments (no shell quoting needed for simple words).
CommandResult run_kinema(const std::vector<std::string>& arguments);

/// Issue 33's bounds (10 s, 2 GB) for a run that must finish, in this build: a sanitizer
/// build runs about ten times slower and holds about three times the memory. A refusal
/// that must come at once gets 10 s here and 30 s there (kBoundCpuSeconds): what it does
/// before refusing (reading, deriving at -O0) took past 10 s under CI's load.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr int kFinishCpuSeconds = 100;
inline constexpr int kBoundCpuSeconds = 30;
inline constexpr long kFinishPeakKilobytes = 6L * 1024 * 1024;
#else
inline constexpr int kFinishCpuSeconds = 10;
inline constexpr int kBoundCpuSeconds = 10;
inline constexpr long kFinishPeakKilobytes = 2L * 1024 * 1024;
#endif

/// Runs kinema under a CPU limit (killed past it: status 137) and reports the largest
/// resident size of any child so far (peak_kilobytes): issue 33's bounds, each case ending
/// within 10 s and 2 GB. `cpu_seconds` kFinishCpuSeconds for a run that must succeed at
/// full size.
CommandResult run_kinema_bounded(const std::vector<std::string>& arguments, int cpu_seconds = kBoundCpuSeconds);

/// True in the sanitizer build. A few cases only run again what other cases run (to compare
/// the bytes of two runs, to last long enough for a progress line, to compile with pdflatex
/// or weigh documents that the golden outputs case shows are the release build's bytes);
/// they are skipped there (`* doctest::skip(kinema_test::kSanitized)`): the release run has
/// them, and under the sanitizers they would run the same code again at ten times the cost
/// (CI's time limit).
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

/// Runs a bash command line (`bash -c`), e.g. with ulimit or redirections; its stdout and stderr are captured.
CommandResult run_shell(const std::string& command_line);

/// word in single quotes for the shell, e.g. a path in a run_shell command line.
std::string shell_quote(const std::string& word);

std::string sample(const std::string& name);     ///< Path of samples/NAME.


/// `kinema loops` of a mechanism as written (its constraint system built for the guesses).
std::string loops_file(const kinema::Mechanism& written);
/// Every bundled sample (file names in samples/).
inline constexpr const char* kSamples[] = {"four_bar.toml", "slider_crank.toml", "piston_driven_crank.toml",
                                           "example_4_1_r_trr.toml", "example_4_2_r_rtr_rrt.toml",
                                           "problem_4_4_six_bar.toml", "problem_3_22_six_bar_sliders.toml",
                                           "problem_4_4_joints.toml", "example_4_1_joints.toml",
                                           "example_4_2_joints.toml", "problem_3_22_joints.toml",
                                           "problem_4_1_parallelogram.toml", "problem_4_1_antiparallelogram.toml",
                                           "triple_rocker_circuit.toml", "robot_arm_seed000.toml",
                                           "rssr_spatial_four_bar.toml", "robot_arm_slider.toml",
                                           "crank_shaper.toml"};

/// Runs `kinema eval SAMPLE --format json [extra]` and returns the parsed document.
nlohmann::json eval_json(const std::string& sample_name, const std::vector<std::string>& extra = {});

/// True when actual agrees with a printed number to one unit of its last digit (the
/// seeds round pi and intermediates, so half a unit would be too strict; where a seed's
/// number is further off, finite differences decide and the sample says so).
bool matches_printed(double actual, const std::string& printed);

/// A small valid four-bar file; tests edit it into bad or hostile variants.
const std::string& four_bar_text();

/// text with the first `from` replaced by `to` (the test fails if `from` is missing).
std::string replaced(const std::string& from, const std::string& to, std::string text = four_bar_text());

/// Problem 4.4 with BC = 0.38 m and CD = 0.35 m (issue 45), whose slider F turns back twice
/// a turn: the vector-loop file, and the joints-and-links file with its sketch the vector-loop
/// file's solved joints at phi = 30 deg.
std::string six_bar_turning_back_text();
std::string six_bar_turning_back_joints_text();

/// An extremum of unknown j found by scanning the position solution over a turn from the
/// file's input value (no rates used): the input (deg in [0, 360)) where the solved
/// coordinate is larger (a maximum) or smaller than at both neighbours `step_deg` away.
struct ScannedExtremum {
  double input_deg = 0;
  double value = 0;  ///< SI.
  bool maximum = false;
};
std::vector<ScannedExtremum> scanned_extrema(const kinema::Model& model, std::size_t j, double step_deg = 0.05);

/// Analysis options with the input's rates given (and threads, SIMD on or off).
kinema::MotionOptions with_rates(double rate, double second_rate, unsigned threads = 1, bool simd = true);

/// The whole content of a file ("" if it cannot be read).
std::string read_file(const std::string& path);

/// This test process's own directory for the files a test writes: ctest runs test cases in
/// parallel processes, and two cases writing the same name in one shared directory read each
/// other's files. Removed when the process ends.
std::filesystem::path scratch_directory();

/// Writes text to a fresh file in the scratch directory and returns its path.
std::string write_temporary(const std::string& name, const std::string& text);

/// An empty directory of that name under the build tree (removed and made again), for tests that
/// look at every file a run leaves.
std::string fresh_directory(const std::string& name);

}  // namespace kinema_test

#define CHECK_PRINTED(actual, printed)                                                  \
  do {                                                                                 \
    const double kinema_actual_ = (actual);                                            \
    INFO("actual " << kinema_actual_ << " vs printed " << printed);                   \
    CHECK(kinema_test::matches_printed(kinema_actual_, printed));                      \
  } while (0)
