// kinema check as a command (run in this process): exit status 0 when every answer is right
// and 1 when some are wrong, the report for people and in JSON, a class table's variant
// (class.json as kinema problems writes it, the fixture written here), and bad input
// (status 2, file:line).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "engine/base/number_format.hpp"
#include "engine/model.hpp"

#include "cli/exit_status.hpp"
#include "cli/run.hpp"
#include "tests/test_support.hpp"

namespace {

using kinema::format_round_trip;

constexpr double kDeg = 3.14159265358979323846 / 180.0;

std::filesystem::path check_directory() {
  const auto directory = kinema_test::scratch_directory() / "check";
  std::filesystem::create_directories(directory);
  return directory;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = (check_directory() / name).string();
  std::ofstream(path) << text;
  return path;
}

struct Checked {
  int status = -1;
  std::string report;  ///< What -o received.
  std::string error;   ///< The message of what it threw.
};

// kinema check ARGUMENTS -o FILE, in process; what it throws mapped as main maps it.
Checked check(std::vector<std::string> arguments) {
  const std::string report = (check_directory() / "report").string();
  std::filesystem::remove(report);
  arguments.insert(arguments.begin(), {"kinema", "check"});
  arguments.insert(arguments.end(), {"-o", report});
  std::vector<char*> argv;
  for (std::string& argument : arguments) argv.push_back(argument.data());
  Checked result;
  try {
    result.status = kinema_cli::run(static_cast<int>(argv.size()), argv.data());
  } catch (const std::exception& error) {
    result.status = kinema_cli::exit_status(error);
    result.error = error.what();
  }
  result.report = kinema_test::read_file(report);
  return result;
}

// The four-bar sample's state at 40 deg, as kinema eval solves it (b edited when given,
// and the driver's rate).
kinema::MotionState four_bar_at_40(const std::string& b = "120 mm", const std::string& rate = "10 rad/s") {
  std::string text = kinema_test::read_file(kinema_test::sample("four_bar.toml"));
  text = kinema_test::replaced("b = \"120 mm\"", "b = \"" + b + "\"", text);
  text = kinema_test::replaced("rate = \"10 rad/s\"", "rate = \"" + rate + "\"", text);
  const kinema::Model model = kinema::load_model(write("four_bar_edited.toml", text), kinema::DerivationScope::evaluation);
  const kinema::MotionTable table = kinema::solve_motion(model, {40 * kDeg});
  REQUIRE(table.status(0) == kinema::Status::ok);
  return table[0];
}

std::string toml_answer(const std::string& quantity, const std::string& value) {
  return "[[answer]]\nquantity = \"" + quantity + "\"\nat = \"40 deg\"\nvalue = \"" + value + "\"\n\n";
}

const std::string kFourBar = kinema_test::sample("four_bar.toml");

}  // namespace

TEST_CASE("kinema check: right answers (TOML, CSV) give status 0; a wrong one status 6 and its mistake") {
  const kinema::MotionState s = four_bar_at_40();
  const std::string omega3 = format_round_trip(s.qd[0]);
  const std::string right = write("right.toml", toml_answer("omega3", omega3 + " rad/s") +
                                                    toml_answer("alpha4", format_round_trip(s.qdd[1])) +
                                                    toml_answer("vP", format_round_trip(s.points[2].speed()) + " m/s"));
  const Checked toml = check({kFourBar, right});
  CHECK(toml.status == kinema_cli::status::success);
  CHECK(toml.report.find("3 of 3 right") != std::string::npos);
  CHECK(toml.report.find("no unit: taken as rad/s^2") != std::string::npos);  // alpha4 was written bare

  const std::string csv = write("right.csv", "quantity,at,value,unit\nomega3,40 deg," + omega3 + ",rad/s\n"
                                             "# a comment\ntheta3,40 deg," + format_round_trip(s.q[0] / kDeg) + "\n");
  CHECK(check({kFourBar, csv}).status == kinema_cli::status::success);

  const std::string wrong = write("wrong.toml", toml_answer("omega3", format_round_trip(-s.qd[0]) + " rad/s") +
                                                    toml_answer("alpha4", format_round_trip(s.qdd[1])));
  const Checked text = check({kFourBar, wrong});
  CHECK(text.status == kinema_cli::status::wrong_answers);
  CHECK(text.report.find("wrong.toml:1: omega3 at 40 deg") != std::string::npos);
  CHECK(text.report.find("likely mistake: sign or sense reversed") != std::string::npos);
  CHECK(text.report.find("1 of 2 right") != std::string::npos);

  const Checked json = check({kFourBar, wrong, "--format", "json"});
  CHECK(json.status == kinema_cli::status::wrong_answers);
  const nlohmann::json report = nlohmann::json::parse(json.report);
  CHECK(report["wrong"] == 1);
  CHECK(report["right"] == 1);
  CHECK(report["tolerance"]["relative"] == 0.01);
  CHECK(report["answers"][0]["right"] == false);
  CHECK(report["answers"][0]["mistake"]["name"] == "sign_reversed");
  CHECK(report["answers"][0]["expected"].get<double>() == s.qd[0]);
  CHECK(report["answers"][1]["right"] == true);
  CHECK(report["answers"][1]["mistake"].is_null());
}

TEST_CASE("kinema check: --tolerance and --sig-figs decide an answer near the edge") {
  const double omega3 = four_bar_at_40().qd[0];
  const std::string near = write("near.toml", toml_answer("omega3", format_round_trip(omega3 * 1.004)));
  CHECK(check({kFourBar, near}).status == kinema_cli::status::success);  // 1 % by default
  CHECK(check({kFourBar, near, "--tolerance", "0.3%"}).status == kinema_cli::status::wrong_answers);
  CHECK(check({kFourBar, near, "--sig-figs", "2"}).status == kinema_cli::status::success);
  CHECK(check({kFourBar, near, "--sig-figs", "4"}).status == kinema_cli::status::wrong_answers);
  CHECK(check({kFourBar, near, "--sig-figs", "2", "--tolerance", "1%"}).status == kinema_cli::status::bad_input);
}

TEST_CASE("kinema check: a class table's variant is the source file with the variant's parameters") {
  std::filesystem::copy_file(kFourBar, check_directory() / "four_bar.toml",
                             std::filesystem::copy_options::overwrite_existing);
  // Variant 2: b = 115 mm and the driver at 60 rpm; three figures.
  const std::string table = write("class.json", R"({"source": "four_bar.toml", "seed": 7, "count": 2,
    "tolerance": {"sig_figs": 3},
    "variants": [
      {"variant": 1, "parameters": {"b": {"si": 0.12, "value": 120, "unit": "mm"}},
       "answers": [{"quantity": "omega3", "at": "40 deg", "at_si": 0.6981317007977318, "si": 0, "value": 0, "unit": "rad/s"}]},
      {"variant": 2, "parameters": {"b": {"si": 0.115, "value": 115, "unit": "mm"},
                                    "omega2": {"si": 6.283185307179586, "value": 60, "unit": "rpm"}},
       "answers": [{"quantity": "omega3", "at": "40 deg", "at_si": 0.6981317007977318, "si": 0, "value": 0, "unit": "rad/s"}]}]})");
  // The variant by hand: the file edited to b = 115 mm, 60 rpm.
  const double omega3 = four_bar_at_40("115 mm", "60 rpm").qd[0];
  const std::string answers = write("variant.toml", "variant = 2\n\n[[answer]]\nquantity = \"omega3\"\nvalue = " +
                                                        format_round_trip(omega3) + "\n");  // at: the key's
  const Checked right = check({table, answers, "--format", "json"});
  CHECK(right.status == kinema_cli::status::success);
  const nlohmann::json report = nlohmann::json::parse(right.report);
  CHECK(report["variant"] == 2);
  CHECK(report["tolerance"]["sig_figs"] == 3);
  CHECK(report["answers"][0]["at"] == "40 deg");
  CHECK(report["answers"][0]["expected"].get<double>() == doctest::Approx(omega3).epsilon(1e-12));

  const std::string bare = write("bare.toml", "[[answer]]\nquantity = \"omega3\"\nvalue = " + format_round_trip(omega3) + "\n");
  CHECK(check({table, bare, "--variant", "2"}).status == kinema_cli::status::success);
  CHECK(check({table, bare, "--variant", "1"}).status == kinema_cli::status::wrong_answers);  // the other variant's b

  // The variant's 60 rpm taken as 60 rad/s.
  const double as_rad = four_bar_at_40("115 mm", "60 rad/s").qd[0];
  const std::string rpm = write("rpm.toml", "[[answer]]\nquantity = \"omega3\"\nvalue = " + format_round_trip(as_rad) + "\n");
  const Checked slip = check({table, rpm, "--variant", "2", "--format", "json"});
  CHECK(slip.status == kinema_cli::status::wrong_answers);
  CHECK(nlohmann::json::parse(slip.report)["answers"][0]["mistake"]["name"] == "rpm_as_rad_per_s");

  SUBCASE("a variant missing, unknown, or given twice apart") {
    const Checked missing = check({table, bare});
    CHECK(missing.status == kinema_cli::status::bad_input);
    CHECK(missing.error.find("give --variant N") != std::string::npos);
    const Checked unknown = check({table, bare, "--variant", "9"});
    CHECK(unknown.status == kinema_cli::status::bad_input);
    CHECK(unknown.error.find("no variant 9; the class table has variants 1, 2") != std::string::npos);
    const Checked apart = check({table, answers, "--variant", "1"});
    CHECK(apart.status == kinema_cli::status::bad_input);
    CHECK(apart.error.find("variant.toml:1: variant = 2, but --variant 1") != std::string::npos);
    CHECK(apart.report.empty());
  }
  SUBCASE("a variant's parameter the source does not write") {
    const std::string bad = write("bad_class.json", R"({"source": "four_bar.toml",
      "variants": [{"variant": 1, "parameters": {"bb": {"si": 0.12}}}]})");
    const Checked result = check({bad, bare, "--variant", "1"});
    CHECK(result.status == kinema_cli::status::bad_input);
    CHECK(result.error.find("bad_class.json: variant 1:") != std::string::npos);
    CHECK(result.error.find("bb") != std::string::npos);
  }
}

TEST_CASE("kinema check: a bad answers file is refused with its file:line (status 2, no report)") {
  const auto refused = [](const std::string& name, const std::string& text, const std::string& part,
                          std::vector<std::string> extra = {}) {
    CAPTURE(name);
    std::vector<std::string> arguments = {kFourBar, write(name, text)};
    arguments.insert(arguments.end(), extra.begin(), extra.end());
    const Checked result = check(arguments);
    CAPTURE(result.error);
    CHECK(result.status == kinema_cli::status::bad_input);
    CHECK(result.report.empty());
    CHECK(result.error.find(part) != std::string::npos);
  };
  refused("syntax.toml", "[[answer]]\nquantity = \"omega3\nvalue = 1\n", "syntax.toml:2: syntax error in the answers file");
  refused("unknown.toml", "\n[[answer]]\nquantity = \"omega9\"\nvalue = 1\n",
          "unknown.toml:2: unknown quantity \"omega9\"; the quantities of");
  refused("no_value.toml", "[[answer]]\nquantity = \"omega3\"\n", "no_value.toml:1: [[answer]] without value");
  refused("key.toml", "[[answer]]\nquantity = \"omega3\"\nvalue = 1\nunit = \"rad/s\"\n",
          "key.toml:4: unknown key \"unit\" in [[answer]]");
  refused("fields.csv", "omega3,40 deg\n", "fields.csv:1: 2 fields");
  refused("unit.csv", "omega3,40 deg,-1.6,furlong\n", "unit.csv:1: value of omega3");
  refused("empty.toml", "# nothing yet\n", "empty.toml: no answers");
  refused("variant.toml", "variant = 3\n[[answer]]\nquantity = \"omega3\"\nvalue = 1\n",
          "variant.toml:1: a variant is one of a class table's");
  refused("no_at.toml", "[[answer]]\nquantity = \"omega3\"\nvalue = 1\n", "is a mechanism file", {"--variant", "1"});
  const Checked missing = check({kFourBar, (check_directory() / "absent.toml").string()});
  CHECK(missing.status == kinema_cli::status::bad_input);
  CHECK(missing.error.find("cannot open the answers file") != std::string::npos);
}

TEST_CASE("kinema check: docs/check.md's example is what it prints for the sample answers") {
  const std::string docs = kinema_test::read_file(kinema_test::sample("../docs/check.md"));
  const std::string command = "$ kinema check samples/four_bar.toml samples/check/four_bar_answers.toml\n";
  const std::size_t begin = docs.find(command);
  REQUIRE(begin != std::string::npos);
  const std::size_t first = begin + command.size();
  const std::string shown = docs.substr(first, docs.find("```", first) - first);
  const Checked result = check({kFourBar, kinema_test::sample("check/four_bar_answers.toml")});
  CHECK(result.status == kinema_cli::status::wrong_answers);
  // The report names the files as given: here by their paths in the source tree.
  std::string report = result.report;
  const std::string samples = kinema_test::sample("");
  for (std::size_t at; (at = report.find(samples)) != std::string::npos;) report.replace(at, samples.size(), "samples/");
  CHECK(report == shown);
}

TEST_CASE("kinema check: the README's and docs/problems.md's example, the set's sample answers, is all right") {
  // The command as both documents give it, run on the files it names.
  const std::string command =
      "kinema check samples/problem_4_4_set.toml samples/check/problem_4_4_answers.toml\n";
  for (const char* document : {"../README.md", "../docs/problems.md"}) {
    CAPTURE(document);
    CHECK(kinema_test::read_file(kinema_test::sample(document)).find(command) != std::string::npos);
  }
  const Checked result =
      check({kinema_test::sample("problem_4_4_set.toml"), kinema_test::sample("check/problem_4_4_answers.toml")});
  CAPTURE(result.error);
  CHECK(result.status == kinema_cli::status::success);
  CHECK(result.report.find(": right") != std::string::npos);
  CHECK(result.report.find(": wrong") == std::string::npos);
}
