// kinema as a user runs it, whole process against whole process (issue 10): a sweep of
// Problem 4.4 to CSV, JSON and npy files, 10^7 values to a pipe, and the four-bar over
// 36,001 values to CSV against a student's SymPy script doing the same job
// (bench/sympy_student_script.py), in one run. Wall time is the best of a few runs;
// memory is the peak resident set of the process (wait4's ru_maxrss).
// Run: ./build/kinema_output_bench [--quick]   (--quick: skips the 10^7-value run)
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

struct Measured {
  double seconds = NAN;
  double megabytes = NAN;  // peak RSS
  long long bytes = 0;     // what came through the pipe, when piped
  bool ok = false;
};

// Runs argv with stdout to /dev/null, or into a pipe that this process drains.
Measured run_once(const std::vector<std::string>& argv, bool pipe_stdout) {
  int fds[2] = {-1, -1};
  if (pipe_stdout && ::pipe(fds) != 0) return {};
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child == 0) {
    const int out = pipe_stdout ? fds[1] : ::open("/dev/null", O_WRONLY);
    ::dup2(out, STDOUT_FILENO);
    if (pipe_stdout) {
      ::close(fds[0]);
      ::close(fds[1]);
    }
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  Measured m;
  if (pipe_stdout) {
    ::close(fds[1]);
    static char buffer[1 << 16];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) > 0;) m.bytes += n;
    ::close(fds[0]);
  }
  int status = 0;
  struct rusage usage {};
  ::wait4(child, &status, 0, &usage);
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.megabytes = usage.ru_maxrss / 1024.0;
  m.ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  return m;
}

// Best time of `runs` (the output file removed before each, as a first run finds it).
Measured best_of(int runs, const std::vector<std::string>& argv, const std::string& output = "", bool pipe = false) {
  Measured best;
  for (int r = 0; r < runs; ++r) {
    if (!output.empty()) std::filesystem::remove(output);
    const Measured m = run_once(argv, pipe);
    if (!m.ok) return m;
    if (!best.ok || m.seconds < best.seconds) best = m;
  }
  return best;
}

void row(const char* what, const Measured& m, double seconds_target, double megabytes_target) {
  if (!m.ok) {
    std::printf("%-58s FAILED\n", what);
    return;
  }
  auto verdict = [](bool met) { return met ? "met" : "MISSED"; };
  std::printf("%-58s %8.3f s", what, m.seconds);
  if (!std::isnan(seconds_target))
    std::printf(" (target %.2f s: %.2fx, %s)", seconds_target, seconds_target / m.seconds, verdict(m.seconds <= seconds_target));
  std::printf("  %6.1f MB", m.megabytes);
  if (!std::isnan(megabytes_target))
    std::printf(" (target %.0f MB, %s)", megabytes_target, verdict(m.megabytes <= megabytes_target));
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const std::string kinema = KINEMA_EXE, source = KINEMA_SOURCE_DIR;
  const std::string six_bar = source + "/samples/problem_4_4_six_bar.toml", four_bar = source + "/samples/four_bar.toml";
  const auto directory = std::filesystem::temp_directory_path() / "kinema_output_bench";
  std::filesystem::create_directories(directory);
  const unsigned cores = std::max(1u, static_cast<unsigned>(::sysconf(_SC_NPROCESSORS_ONLN)));
  std::printf("kinema eval, whole process (best of 3; peak resident memory); %u cores, --threads default (one per core)\n\n",
              cores);
  const double none = NAN;
  for (const auto& [format, seconds] : {std::pair{"csv", 0.5}, std::pair{"json", 1.0}, std::pair{"npy", 0.15}}) {
    const std::string out = (directory / (std::string("six_bar.") + format)).string();
    const Measured m = best_of(3, {kinema, "eval", six_bar, "--sweep", "0:360:0.001", "--format", format, "-o", out}, out);
    const std::string what = std::string("Problem 4.4, 360,001 values -> ") + format + " file (" +
                             std::to_string(std::filesystem::exists(out) ? std::filesystem::file_size(out) >> 20 : 0) + " MB)";
    row(what.c_str(), m, seconds, format == std::string("npy") ? none : 50.0);
    std::filesystem::remove(out);
  }
  {
    const Measured one = best_of(3, {kinema, "eval", six_bar, "--sweep", "0:360:0.001", "--format", "csv", "--threads", "1",
                                     "-o", (directory / "one.csv").string()}, (directory / "one.csv").string());
    row("  the same CSV on one thread (--threads 1)", one, none, 50.0);
    std::filesystem::remove(directory / "one.csv");
  }
  if (!quick) {
    const Measured ten_million = best_of(1, {kinema, "eval", six_bar, "--sweep", "0:360:0.000036", "--format", "csv"}, "", true);
    const std::string what = "Problem 4.4, 10^7 values -> CSV through a pipe (" + std::to_string(ten_million.bytes >> 20) + " MB)";
    row(what.c_str(), ten_million, none, 50.0);
  }
  // The student's job against kinema's, whole process against whole process.
  const std::string csv = (directory / "four_bar.csv").string(), student_csv = (directory / "student.csv").string();
  const Measured k = best_of(5, {kinema, "eval", four_bar, "--sweep", "0:360:0.01", "--format", "csv", "-o", csv}, csv);
  const Measured s = best_of(1, {"/usr/bin/python3", source + "/bench/sympy_student_script.py", student_csv}, student_csv);
  row("four-bar, 36,001 values -> CSV file: kinema", k, none, none);
  row("  the same with a SymPy script (derive, lambdify, Newton, print)", s, none, none);
  if (k.ok && s.ok) {
    const double ratio = s.seconds / k.seconds;
    std::printf("  kinema is %.0fx faster (target 300x: %s); memory %.1f MB against %.1f MB\n", ratio,
                ratio >= 300 ? "met" : "MISSED", k.megabytes, s.megabytes);
  }
  // The same command for one value: what the run costs before its rows (the table format
  // would add work of its own: the mechanism's toggles for its header).
  const Measured start = best_of(5, {kinema, "eval", four_bar, "--angle", "40", "--format", "csv"});
  row("  of which a process that solves one value (start, read, derive, compile)", start, none, none);
  // The floor of this machine: a process that computes nothing and only copies kinema's
  // finished CSV into a new file. 300x needs kinema within (SymPy / 300) / floor of it.
  const std::string copy = (directory / "copy.csv").string();
  const Measured floor = best_of(5, {"/bin/cp", csv, copy}, copy);
  row("  the floor: /bin/cp of that finished CSV to a new file", floor, none, none);
  if (floor.ok && s.ok)
    std::printf("  SymPy / floor = %.0fx: at 300x kinema may take %.2fx the time of copying its own output\n",
                s.seconds / floor.seconds, s.seconds / 300 / floor.seconds);
  // The floor with the libraries kinema must link: start-up and writing the same bytes,
  // nothing computed. What 300x leaves after it is the time for everything kinema does.
  const std::string bytes = std::to_string(std::filesystem::exists(csv) ? std::filesystem::file_size(csv) : 0);
  const Measured linked = best_of(5, {FLOOR_WRITER_EXE, bytes, copy}, copy);
  row("  the floor with GiNaC linked: start, then write as many bytes", linked, none, none);
  if (linked.ok && s.ok)
    std::printf("  at 300x (%.1f ms in all) that leaves %.1f ms to read, derive, solve 36,001 values and format 1.2 million numbers\n",
                s.seconds / 300 * 1e3, (s.seconds / 300 - linked.seconds) * 1e3);
  std::filesystem::remove_all(directory);
  return 0;
}
