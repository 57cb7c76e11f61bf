#include "tests/test_support.hpp"

#include "engine/base/number_format.hpp"
#include "linkages/vector_loop_file.hpp"
#include "readers/mechanism_file.hpp"

#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace kinema_test {

std::string shell_quote(const std::string& word) {
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

namespace {

// Runs a /bin/sh command with stdout and stderr captured in files.
CommandResult run_captured(std::string command) {
  static int counter = 0;
  const auto directory = scratch_directory();
  const std::string stem = (directory / ("run" + std::to_string(::getpid()) + "_" + std::to_string(counter++))).string();
  command += " > " + shell_quote(stem + ".out") + " 2> " + shell_quote(stem + ".err");
  const int raw = std::system(command.c_str());
  CommandResult result;
  result.exit_status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  result.out = read_file(stem + ".out");
  result.err = read_file(stem + ".err");
  std::remove((stem + ".out").c_str());
  std::remove((stem + ".err").c_str());
  return result;
}

}  // namespace

std::string read_file(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

const std::string& four_bar_text() {
  static const std::string text = R"toml(title = "four-bar"
[parameters]
a = "40 mm"
b = "120 mm"
c = "80 mm"
d = "100 mm"
[input]
name = "theta2"
value = "40 deg"
rate = "10 rad/s"
[unknowns]
theta3 = "20 deg"
theta4 = "80 deg"
[loops]
ABCD = "a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d"
[points]
P = "a*exp(I*theta2)"
)toml";
  return text;
}

std::string replaced(const std::string& from, const std::string& to, std::string text) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("test text has no \"" + from + "\"");
  return text.replace(at, from.size(), to);
}

CommandResult run_kinema(const std::vector<std::string>& arguments) {
  std::string command = shell_quote(KINEMA_EXE);
  for (const auto& argument : arguments) command += " " + shell_quote(argument);
  return run_captured(command);
}

CommandResult run_shell(const std::string& command_line) {
  return run_captured("bash -c " + shell_quote(command_line));
}

CommandResult run_kinema_bounded(const std::vector<std::string>& arguments, int cpu_seconds) {
  std::string command = "ulimit -t " + std::to_string(cpu_seconds) + "; exec " + shell_quote(KINEMA_EXE);
  for (const auto& argument : arguments) command += " " + shell_quote(argument);
  CommandResult result = run_shell(command);
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  result.peak_kilobytes = usage.ru_maxrss;
  return result;
}

kinema::MotionOptions with_rates(double rate, double second_rate, unsigned threads, bool simd) {
  kinema::MotionOptions options;
  options.rate = rate;
  options.second_rate = second_rate;
  options.threads = threads;
  options.simd = simd;
  return options;
}

std::string sample(const std::string& name) { return std::string(KINEMA_SAMPLES_DIR) + "/" + name; }

std::string six_bar_turning_back_text() {
  std::string text = read_file(sample("problem_4_4_six_bar.toml"));
  text = replaced(R"(BC = "0.400 m")", R"(BC = "0.38 m")", text);
  return replaced(R"(CD = "0.370 m")", R"(CD = "0.35 m")", text);
}

std::string six_bar_turning_back_joints_text() {
  const kinema::Model loops = kinema::make_model(kinema::read_mechanism_text(six_bar_turning_back_text(), "six.toml"));
  const kinema::MotionTable at = kinema::solve_motion(loops, loops.system.input.values);
  if (at.status(0) != kinema::Status::ok) throw std::runtime_error("the six-bar does not assemble at its file value");
  const auto coordinate = [&](const std::string& point, int k) {
    for (std::size_t p = 0; p < loops.system.points.size(); ++p)
      if (loops.system.points[p].name == point) return kinema::format_round_trip(at[0].points[p].position[k]) + " m";
    throw std::runtime_error("no point " + point);
  };
  std::string text = read_file(sample("problem_4_4_joints.toml"));
  text = replaced(R"(BC = "0.400 m")", R"(BC = "0.38 m")", text);
  text = replaced(R"(CD = "0.370 m")", R"(CD = "0.35 m")", text);
  text = replaced(R"(C = { at = ["-0.0689445 m", "0.422073 m"] })",
                  "C = { at = [\"" + coordinate("C", 0) + "\", \"" + coordinate("C", 1) + "\"] }", text);
  text = replaced(R"(E = { at = ["-0.298288 m", "0.404712 m"] })",
                  "E = { at = [\"" + coordinate("E", 0) + "\", \"" + coordinate("E", 1) + "\"] }", text);
  for (int k = 0; k < 2; ++k) text = replaced("\"0.186177 m\"", "\"" + coordinate("F", 1) + "\"", text);  // F and F5
  return text;
}

std::vector<ScannedExtremum> scanned_extrema(const kinema::Model& model, std::size_t j, double step_deg) {
  const double first = model.system.input.values.empty() ? 0.0 : model.system.input.values.front();
  const int steps = static_cast<int>(std::lround(360 / step_deg));
  std::vector<double> inputs;
  for (int k = -1; k <= steps + 1; ++k) inputs.push_back(first + k * step_deg * M_PI / 180);
  const kinema::MotionTable turn = kinema::solve_motion(model, inputs);
  std::vector<ScannedExtremum> found;
  for (int k = 1; k <= steps; ++k) {
    const auto row = std::size_t(k);
    if (turn.status(row - 1) == kinema::Status::unassembled || turn.status(row) == kinema::Status::unassembled ||
        turn.status(row + 1) == kinema::Status::unassembled)
      continue;
    const double before = turn.q(row - 1)[Eigen::Index(j)], here = turn.q(row)[Eigen::Index(j)],
                 after = turn.q(row + 1)[Eigen::Index(j)];
    const bool maximum = here > before && here >= after, minimum = here < before && here <= after;
    if (!maximum && !minimum) continue;
    double deg = std::fmod(turn.input(row) * 180 / M_PI, 360.0);
    if (deg < 0) deg += 360;
    found.push_back({deg, here, maximum});
  }
  std::sort(found.begin(), found.end(), [](const ScannedExtremum& a, const ScannedExtremum& b) { return a.input_deg < b.input_deg; });
  return found;
}

std::string loops_file(const kinema::Mechanism& written) {
  return kinema::vector_loop_file(written, kinema::build_constraint_system(written));
}

nlohmann::json eval_json(const std::string& sample_name, const std::vector<std::string>& extra) {
  std::vector<std::string> arguments = {"eval", sample(sample_name), "--format", "json"};
  arguments.insert(arguments.end(), extra.begin(), extra.end());
  const CommandResult result = run_kinema(arguments);
  if (result.exit_status != 0) {
    throw std::runtime_error("kinema eval " + sample_name + " failed: " + result.err);
  }
  return nlohmann::json::parse(result.out);
}

bool matches_printed(double actual, const std::string& printed) {
  const double value = std::stod(printed);
  const auto dot = printed.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(printed.size() - dot - 1);
  const double last_digit = std::pow(10.0, -decimals);
  const double tolerance = last_digit * (1 + 1e-9);
  return std::fabs(actual - value) <= tolerance;
}

namespace {

// Removes the process's scratch directory at exit, once it was made.
struct ScratchDirectory {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / "kinema_tests" / ("p" + std::to_string(::getpid()));
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

std::filesystem::path scratch_directory() {
  static const ScratchDirectory scratch;
  std::filesystem::create_directories(scratch.path);
  return scratch.path;
}

std::string write_temporary(const std::string& name, const std::string& text) {
  const auto directory = scratch_directory();
  const std::string path = (directory / name).string();
  std::ofstream(path) << text;
  return path;
}

std::string fresh_directory(const std::string& name) {
  const auto directory = std::filesystem::path(KINEMA_TEST_WORK_DIR) / name;
  std::filesystem::remove_all(directory);
  std::filesystem::create_directories(directory);
  return directory.string();
}

}  // namespace kinema_test
