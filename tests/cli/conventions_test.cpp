// The command line as a shell user sees it: --version, one-line usage errors
// with status 2, and output that is written completely or not at all (status 5).
#include <doctest/doctest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "tests/test_support.hpp"

namespace {

using kinema_test::run_kinema;
using kinema_test::run_shell;
using kinema_test::shell_quote;

const std::string kinema_exe = shell_quote(KINEMA_EXE);

// The names of the files in a directory.
std::set<std::string> files_in(const std::string& directory) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(directory)) names.insert(entry.path().filename().string());
  return names;
}

// Status 2, nothing on stdout, one line on stderr with each part and the help to read.
void check_usage_error(const std::vector<std::string>& arguments, const std::vector<std::string>& parts,
                       const std::string& help) {
  std::string command_line = "kinema";
  for (const auto& argument : arguments) command_line += " " + argument;
  CAPTURE(command_line);
  const auto result = run_kinema(arguments);
  CAPTURE(result.err);
  CHECK(result.exit_status == 2);
  CHECK(result.out.empty());
  CHECK(result.err.rfind("kinema: usage error: ", 0) == 0);
  CHECK(result.err.find('\n') == result.err.size() - 1);  // exactly one line
  CHECK(result.err.find("; run '" + help + "'\n") != std::string::npos);
  for (const auto& part : parts) {
    CAPTURE(part);
    CHECK(result.err.find(part) != std::string::npos);
  }
}

// Status 5, nothing on stdout, one line on stderr naming the path (then `reason`) and
// saying nothing was written.
void check_refused_output(const kinema_test::CommandResult& result, const std::string& path,
                          const std::string& reason = "") {
  CAPTURE(result.err);
  CHECK(result.exit_status == 5);
  CHECK(result.out.empty());
  CHECK(result.err.rfind("kinema: error: cannot write " + path + ": " + reason, 0) == 0);
  CHECK(result.err.find("nothing was written") != std::string::npos);
  CHECK(result.err.find('\n') == result.err.size() - 1);
}

}  // namespace

TEST_CASE("kinema --version prints the version and exits 0") {
  const auto result = run_kinema({"--version"});
  CHECK(result.exit_status == 0);
  CHECK(result.out == std::string("kinema ") + KINEMA_VERSION + "\n");
  CHECK(result.err.empty());
}

TEST_CASE("--help prints help on stdout and exits 0") {
  const auto help = run_kinema({"--help"});
  CHECK(help.exit_status == 0);
  CHECK(help.out.find("Usage: kinema [OPTIONS] SUBCOMMAND") != std::string::npos);
  CHECK(help.out.find("--version") != std::string::npos);
  CHECK(help.err.empty());
  const auto eval_help = run_kinema({"eval", "--help"});
  CHECK(eval_help.exit_status == 0);
  CHECK(eval_help.out.find("Usage: kinema eval [OPTIONS] FILE") != std::string::npos);
  CHECK(eval_help.out.find("--threads") != std::string::npos);
  CHECK(eval_help.err.empty());
}

// The front door: the program's help and each command's name the three forms a
// mechanism file can take.
TEST_CASE("--help and each command's help name vector loops, joints and links and spatial chains") {
  for (const std::vector<std::string>& arguments :
       std::vector<std::vector<std::string>>{{"--help"}, {"derive", "--help"}, {"eval", "--help"}, {"latex", "--help"},
                                             {"codegen", "--help"}, {"loops", "--help"}}) {
    const auto help = run_kinema(arguments);
    CAPTURE(arguments.front());
    REQUIRE(help.exit_status == 0);
    // CLI11 wraps long help text: compare with runs of white space as one space.
    std::string text;
    for (char c : help.out) {
      const bool space = c == ' ' || c == '\n' || c == '\t';
      if (!space) text += c;
      else if (!text.empty() && text.back() != ' ') text += ' ';
    }
    for (const char* form : {"vector loops", "joints and links", "spatial chain"}) {
      CAPTURE(form);
      CHECK(text.find(form) != std::string::npos);
    }
  }
}

TEST_CASE("usage errors exit 2 with one line that says what is wrong and what to do") {
  const std::string file = kinema_test::sample("four_bar.toml");
  check_usage_error({}, {"a command is required", "derive, eval, latex, codegen"}, "kinema --help");
  check_usage_error({"eval"}, {"eval: FILE is required"}, "kinema eval --help");
  check_usage_error({"derive"}, {"derive: FILE is required"}, "kinema derive --help");
  check_usage_error({"codegen", file}, {"codegen: --output is required"}, "kinema codegen --help");
  check_usage_error({"eval", file, "--bogus"}, {"eval: unknown option \"--bogus\""}, "kinema eval --help");
  check_usage_error({"--bogus"}, {"unknown option \"--bogus\""}, "kinema --help");
  check_usage_error({"eval", file, "extra.toml"}, {"eval: unexpected argument \"extra.toml\""}, "kinema eval --help");
  check_usage_error({"eval", file, "--threads", "0"}, {"eval: --threads", "0", "1 to 256"}, "kinema eval --help");
  check_usage_error({"eval", file, "--threads", "x"}, {"eval: --threads", "x"}, "kinema eval --help");
  check_usage_error({"eval", file, "--threads"}, {"eval: --threads needs a value"}, "kinema eval --help");
  check_usage_error({"eval", file, "--format", "bogus"}, {"eval: --format", "bogus", "table,csv,json"},
                    "kinema eval --help");
  check_usage_error({"frob", file}, {"unknown command \"frob\"", "derive, eval, latex, codegen"}, "kinema --help");
  // An empty value (a shell variable not set) was taken as the option left out: -o "" wrote
  // to stdout, --sweep "" ran the file's values (audit 2026-11-24).
  const std::string arm = kinema_test::sample("robot_arm_seed000.toml");
  for (const auto& [command, option] : std::vector<std::pair<std::string, std::string>>{
           {"eval", "-o"}, {"eval", "--sweep"}, {"eval", "--angle"}, {"eval", "--circuit"}, {"eval", "--input"},
           {"eval", "--precision"}, {"eval", "--threads"},
           {"derive", "--basis"}, {"derive", "-o"}, {"latex", "--at"}, {"codegen", "--namespace"}, {"loops", "-o"}}) {
    std::vector<std::string> arguments = {command, command == "eval" || command == "loops" ? file : arm, option, ""};
    if (command == "codegen") arguments.insert(arguments.end(), {"-o", "out.hpp"});
    check_usage_error(arguments, {command + ": ", "an empty value; give one or leave the option out"},
                      "kinema " + command + " --help");
  }
}

TEST_CASE("-o writes the whole output, replaces a previous file and keeps its mode") {
  const std::string directory = kinema_test::fresh_directory("cli_output_replaced");
  const std::string path = directory + "/out.csv";
  std::ofstream(path) << "previous text\n";
  std::filesystem::permissions(path, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write |
                                         std::filesystem::perms::group_read);
  const auto to_stdout = run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--format", "csv"});
  const auto to_file = run_kinema({"eval", kinema_test::sample("four_bar.toml"), "--format", "csv", "-o", path});
  REQUIRE(to_stdout.exit_status == 0);
  CHECK(to_file.exit_status == 0);
  CHECK(to_file.out.empty());
  CHECK(kinema_test::read_file(path) == to_stdout.out);
  CHECK((std::filesystem::status(path).permissions() & std::filesystem::perms::all) ==
        (std::filesystem::perms::owner_read | std::filesystem::perms::owner_write | std::filesystem::perms::group_read));
  CHECK(files_in(directory) == std::set<std::string>{"out.csv"});  // no temporary left
}

TEST_CASE("-o into a missing directory exits 5, names the path and writes nothing") {
  const std::string directory = kinema_test::fresh_directory("cli_output_missing_directory");
  // "no/../out.csv": the shell's > refuses it (no is looked up); it was written as out.csv.
  for (const std::string& path : {directory + "/no/such/out.csv", directory + "/no/../out.csv"}) {
    check_refused_output(run_kinema({"eval", kinema_test::sample("four_bar.toml"), "-o", path}), path,
                         "No such file or directory");
    CHECK(files_in(directory).empty());
  }
}

TEST_CASE("-o onto a directory exits 5 and leaves the directory as it was") {
  const std::string directory = kinema_test::fresh_directory("cli_output_onto_directory");
  std::filesystem::create_directory(directory + "/out");
  const auto result = run_kinema({"eval", kinema_test::sample("four_bar.toml"), "-o", directory + "/out"});
  CAPTURE(result.err);
  CHECK(result.exit_status == 5);
  CHECK(result.err.find("cannot write " + directory + "/out: ") != std::string::npos);
  CHECK(files_in(directory) == std::set<std::string>{"out"});
  CHECK(files_in(directory + "/out").empty());
}

// Audit 2026-11-24: the temporary-and-rename replaced a file its user may not write (a
// rename asks only the directory). Now -o asks what the shell's > asks, before any work.
// As root that is nothing (root writes a 0444 file, as with >); the refusal is run as
// the user nobody when the tests run as root (setpriv), as the user itself otherwise.
TEST_CASE("-o onto a file the user may not write is refused before any work, as the shell refuses it") {
  const std::string directory = kinema_test::fresh_directory("cli_output_read_only");
  std::filesystem::permissions(directory, std::filesystem::perms::all);  // anyone may make files here
  const std::string mechanism = directory + "/m.toml", path = directory + "/ro.csv";
  std::filesystem::copy_file(kinema_test::sample("four_bar.toml"), mechanism);
  const auto make_read_only = [&] {
    std::filesystem::remove(path);
    std::ofstream(path) << "old\n";
    std::filesystem::permissions(path, std::filesystem::perms::owner_read | std::filesystem::perms::group_read |
                                           std::filesystem::perms::others_read);
  };
  const bool root = ::geteuid() == 0;
  // Not root: the user itself; root: nobody, if it can run the program from where it is.
  const std::string as_user = root ? "setpriv --reuid=nobody --regid=nogroup --clear-groups " : "";
  const bool runs = run_shell(as_user + kinema_exe + " --version").exit_status == 0;
  if (!runs) {
    MESSAGE("not run: the user nobody cannot run " << KINEMA_EXE << " (setpriv missing or the path closed to it); "
            "only root's case below is tested");
  } else {
    make_read_only();
    // A mechanism that cannot be assembled: status 3 had it been solved before the check.
    const std::string unassembled = directory + "/reach.toml";
    std::ofstream(unassembled) << kinema_test::replaced("d = \"100 mm\"", "d = \"400 mm\"");
    for (const std::string& file : {mechanism, unassembled}) {
      CAPTURE(file);
      const auto result = run_shell(as_user + kinema_exe + " eval " + shell_quote(file) + " -o " + shell_quote(path));
      CAPTURE(result.err);
      CHECK(result.exit_status == 5);
      CHECK(result.out.empty());
      CHECK(result.err == "kinema: error: cannot write " + path + ": Permission denied; nothing was written\n");
      CHECK(kinema_test::read_file(path) == "old\n");
      CHECK(files_in(directory) == std::set<std::string>{"m.toml", "reach.toml", "ro.csv"});  // no temporary
    }
  }
  if (root) {
    // Root may write it, as with the shell's >: it is replaced and keeps its mode.
    make_read_only();
    const auto result = run_kinema({"eval", mechanism, "--format", "csv", "-o", path});
    CHECK(result.exit_status == 0);
    CHECK(kinema_test::read_file(path).rfind("theta2 [deg]", 0) == 0);
    CHECK((std::filesystem::status(path).permissions() & std::filesystem::perms::all) ==
          (std::filesystem::perms::owner_read | std::filesystem::perms::group_read | std::filesystem::perms::others_read));
  }
}

// Audit 2026-11-24: a link whose target did not exist was replaced by a regular file.
// Following it instead would make a file wherever the link points (one planted in /tmp
// by another user): refused, the link left as it was. /dev/stdout into a pipe is a link
// that exists and is written.
TEST_CASE("-o through a dangling symbolic link is refused and the link kept - -o /dev/stdout into a pipe is written") {
  const std::string directory = kinema_test::fresh_directory("cli_output_dangling_link");
  const std::string mechanism = kinema_test::sample("four_bar.toml");
  const auto expected = run_kinema({"eval", mechanism});
  REQUIRE(expected.exit_status == 0);
  std::filesystem::create_symlink("made.txt", directory + "/link.txt");
  std::filesystem::create_symlink("loop_b", directory + "/loop_a");
  std::filesystem::create_symlink("loop_a", directory + "/loop_b");
  for (const std::string name : {"link.txt", "loop_a"}) {
    const auto result = run_kinema({"eval", mechanism, "-o", directory + "/" + name});
    CAPTURE(result.err);
    CHECK(result.exit_status == 5);
    CHECK(result.err.rfind("kinema: error: cannot write " + directory + "/" + name + ": ", 0) == 0);
    CHECK(result.err.find("nothing was written") != std::string::npos);
    CHECK(std::filesystem::is_symlink(directory + "/" + name));
  }
  CHECK(run_kinema({"eval", mechanism, "-o", directory + "/link.txt"}).err.find("symbolic link to a file that does not exist") !=
        std::string::npos);
  CHECK(files_in(directory) == std::set<std::string>{"link.txt", "loop_a", "loop_b"});
  const auto piped = run_shell(kinema_exe + " eval " + shell_quote(mechanism) + " -o /dev/stdout | cat");
  CHECK(piped.exit_status == 0);
  CHECK(piped.out == expected.out);
}

// `ulimit -f 1` (1024 bytes): writes past the limit fail with EFBIG, the way a full
// disk fails them (kinema ignores SIGXFSZ, which would kill it mid-file); a 361-row
// table is far longer.
const std::string kLimitedSweep =
    "ulimit -f 1; " + kinema_exe + " eval " + shell_quote(kinema_test::sample("four_bar.toml")) +
    " --sweep 0:360:1";

TEST_CASE("-o under a file-size limit exits 5, keeps the previous file and leaves no temporary") {
  const std::string directory = kinema_test::fresh_directory("cli_output_file_size_limit");
  const std::string path = directory + "/out.txt";
  const std::string previous = "previous text, shorter than the limit\n";
  std::ofstream(path) << previous;
  check_refused_output(run_shell(kLimitedSweep + " -o " + shell_quote(path)), path);
  CHECK(kinema_test::read_file(path) == previous);
  CHECK(files_in(directory) == std::set<std::string>{"out.txt"});
}

TEST_CASE("stdout redirected to a file under a file-size limit exits 5") {
  const std::string directory = kinema_test::fresh_directory("cli_stdout_file_size_limit");
  const std::string path = directory + "/out2.txt";
  std::ofstream(path) << "previous text\n";
  const auto result = run_shell(kLimitedSweep + " > " + shell_quote(path));
  CAPTURE(result.err);
  CHECK(result.exit_status == 5);
  CHECK(result.err.rfind("kinema: error: cannot write standard output: ", 0) == 0);
  CHECK(result.err.find('\n') == result.err.size() - 1);
}

// A run ended by a signal (kill, a closed terminal) while it writes OUT's temporary
// removes it: no half-written file remains, and the status is the signal's.
TEST_CASE("-o: a run killed while writing leaves neither OUT nor its temporary") {
  const std::string directory = kinema_test::fresh_directory("cli_output_killed");
  // TERM and HUP as a user or terminal sends them; ALRM (timeout -s ALRM), XCPU (ulimit
  // -t), USR1 and PIPE: every signal that ends the process by default.
  for (const auto& [signal, number] : {std::pair<std::string, int>{"TERM", 15}, {"HUP", 1}, {"ALRM", 14}, {"XCPU", 24},
                                       {"USR1", 10}, {"PIPE", 13}}) {
    CAPTURE(signal);
    const std::string path = directory + "/out.csv";
    // 3.6 * 10^7 values: tens of seconds, killed once its temporary has appeared.
    const auto result = run_shell(
        kinema_exe + " eval " + shell_quote(kinema_test::sample("four_bar.toml")) +
        " --sweep 0:360:0.00001 --format csv -o " + shell_quote(path) + " & pid=$!; " +
        "for i in $(seq 400); do ls -A " + shell_quote(directory) + " | grep -q '^.kinema-' && break; sleep 0.05; done; " +
        "sleep 0.2; kill -" + signal + " $pid; wait $pid; echo \"status $?\"");
    CAPTURE(result.err);
    CHECK(result.out == "status " + std::to_string(128 + number) + "\n");
    CHECK(files_in(directory).empty());
  }
}

// Issue 9, finding 3: -o never replaces a FIFO, a device or a symbolic link with a
// regular file, never follows a predictable temporary name, never overwrites the
// mechanism file. All inside a fresh directory (never the machine's own /dev).
TEST_CASE("-o writes into a FIFO, through a symlink, past a planted .tmp link, and refuses the input file") {
  const std::string directory = kinema_test::fresh_directory("output_targets");
  const std::string mechanism = directory + "/m.toml";
  std::filesystem::copy_file(kinema_test::sample("four_bar.toml"), mechanism);
  const std::string original = kinema_test::read_file(mechanism);
  const auto expected = run_kinema({"eval", mechanism});
  REQUIRE(expected.exit_status == 0);

  // A FIFO gets the text and stays a FIFO (a reader in the background collects it).
  const std::string fifo = directory + "/pipe";
  const std::string received = directory + "/received.txt";
  const auto piped = run_shell("mkfifo " + shell_quote(fifo) + " && { cat " + shell_quote(fifo) + " > " +
                               shell_quote(received) + " & } && " + shell_quote(KINEMA_EXE) + " eval " +
                               shell_quote(mechanism) + " -o " + shell_quote(fifo) + " && wait");
  CHECK(piped.exit_status == 0);
  CHECK(std::filesystem::is_fifo(fifo));
  CHECK(kinema_test::read_file(received) == expected.out);

  // A symbolic link stays a link; its target gets the text.
  const std::string victim = directory + "/target.txt", link = directory + "/link.txt";
  std::ofstream(victim) << "old\n";
  std::filesystem::create_symlink(victim, link);
  CHECK(run_kinema({"eval", mechanism, "-o", link}).exit_status == 0);
  CHECK(std::filesystem::is_symlink(link));
  CHECK(kinema_test::read_file(victim) == expected.out);

  // A link planted at OUT.tmp is not followed (temporaries are made with O_EXCL).
  const std::string planted_target = directory + "/planted_target.txt";
  std::ofstream(planted_target) << "keep\n";
  std::filesystem::create_symlink(planted_target, directory + "/result.csv.tmp");
  CHECK(run_kinema({"eval", mechanism, "-o", directory + "/result.csv"}).exit_status == 0);
  CHECK(kinema_test::read_file(planted_target) == "keep\n");
  CHECK(kinema_test::read_file(directory + "/result.csv") == expected.out);

  // -o of the mechanism file itself: refused, the file as it was.
  const auto self = run_kinema({"eval", mechanism, "-o", mechanism});
  CHECK(self.exit_status == 2);
  CHECK(self.err.find("is the mechanism file itself") != std::string::npos);
  CHECK(kinema_test::read_file(mechanism) == original);
  // Leftover temporaries: none.
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    CHECK(entry.path().filename().string().rfind(".kinema-", 0) != 0);
}

// Issue 9, finding 17: the same input gives the same output, byte for byte, from run
// to run (GiNaC orders terms by hashes that include addresses; the tape orders
// operands itself and the CLI runs with address randomisation off).
TEST_CASE("every command prints the same bytes in every run, for every sample" * doctest::skip(kinema_test::kSanitized)) {
  for (const auto& entry : std::filesystem::directory_iterator(KINEMA_SAMPLES_DIR)) {
    if (entry.path().extension() != ".toml") continue;  // a folder of what is read with them (samples/check)
    const std::string path = entry.path().string();
    CAPTURE(path);
    const std::vector<std::vector<std::string>> commands = {
        {"derive", path},
        {"derive", path, "--format", "latex"},
        {"eval", path, "--format", "csv", "--sweep", entry.path().stem().string().find("piston") == std::string::npos
                                                         ? "0:360:0.5"
                                                         : "100:200:0.25"},
        {"eval", path, "--format", "json"},
        {"latex", path}};
    for (const auto& command : commands) {
      CAPTURE(command[0]);
      const auto first = run_kinema(command);
      CHECK(first.exit_status == 0);
      for (int run = 0; run < 3; ++run) CHECK(run_kinema(command).out == first.out);
    }
  }
}
