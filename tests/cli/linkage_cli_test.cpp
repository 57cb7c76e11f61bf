// The joints-and-links form through the kinema program: `kinema loops` writes the
// vector-loop file kinema found, which evaluates to the same bytes; a structural
// mistake is an input error (status, file:line, no output file).
#include <doctest/doctest.h>

#include <filesystem>

#include "test_support.hpp"

TEST_CASE("kinema loops: the vector loops of a joints-and-links sample evaluate to the same CSV") {
  for (const char* name : {"problem_4_4_joints.toml", "example_4_1_joints.toml", "example_4_2_joints.toml",
                           "problem_3_22_joints.toml"}) {
    CAPTURE(name);
    const std::string directory = kinema_test::fresh_directory("linkage_loops_cli");
    const std::string loops = directory + "/loops.toml";
    const auto written = kinema_test::run_kinema({"loops", kinema_test::sample(name), "-o", loops});
    REQUIRE(written.exit_status == 0);
    CHECK(written.out.empty());
    const std::string text = kinema_test::read_file(loops);
    CHECK(text.find("[loops]") != std::string::npos);
    CHECK(text.find("[joints]") == std::string::npos);
    const auto drawn = kinema_test::run_kinema({"eval", kinema_test::sample(name), "--sweep", "20:160:10", "--format", "csv"});
    const auto by_loops = kinema_test::run_kinema({"eval", loops, "--sweep", "20:160:10", "--format", "csv"});
    REQUIRE(drawn.exit_status == 0);
    REQUIRE(by_loops.exit_status == 0);
    CHECK(drawn.out == by_loops.out);
  }
}

TEST_CASE("kinema loops and eval: a joints-and-links file with a mistake writes nothing") {
  const std::string text = kinema_test::read_file(kinema_test::sample("problem_4_4_joints.toml"));
  const std::string bad = kinema_test::write_temporary(
      "linkage_bad.toml", kinema_test::replaced(R"(4 = { joints = ["F", "E"], length = "EF", angle = "phi4" })",
                                                R"(4 = { joints = ["F"], angle = "phi4" })", text));
  for (const char* command : {"loops", "eval", "derive", "latex"}) {
    CAPTURE(command);
    const std::string output = bad + ".out";
    std::filesystem::remove(output);
    const auto result = kinema_test::run_kinema({command, bad, "-o", output});
    CHECK(result.exit_status == 2);  // bad input (cli/exit_status.hpp), not an internal error
    CHECK_FALSE(std::filesystem::exists(output));
    CHECK(result.err.find("linkage_bad.toml:") != std::string::npos);
    CHECK(result.err.find("joint \"E\" is used by link 3 only") != std::string::npos);
  }
}
