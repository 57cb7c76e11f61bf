// The README says what is true: its library example is examples/library_usage.cpp
// as it is (that file is built against an installed kinema and run by the
// "package: ..." test), the folders its "How it works" names exist, and its first
// example output is the program's.
#include <doctest/doctest.h>

#include <filesystem>

#include "test_support.hpp"

TEST_CASE("README shows examples/library_usage.cpp verbatim, and the folders it names exist") {
  const std::string readme = kinema_test::read_file(kinema_test::sample("../README.md"));
  const std::string example = kinema_test::read_file(kinema_test::sample("../examples/library_usage.cpp"));
  REQUIRE(!readme.empty());
  REQUIRE(example.find("kinema::analyse(model") != std::string::npos);
  CHECK(readme.find("```cpp\n" + example + "```") != std::string::npos);
  for (const char* folder : {"loops", "engine/symbolic", "engine/numeric", "engine/report", "engine/printers/text",
                             "engine/printers/data", "engine/printers/latex", "engine/printers/code", "cli"}) {
    CAPTURE(folder);
    CHECK(std::filesystem::is_directory(kinema_test::sample(std::string("../") + folder)));
  }
}

TEST_CASE("README's \"What it prints\" is what the command prints") {
  const std::string readme = kinema_test::read_file(kinema_test::sample("../README.md"));
  const auto result = kinema_test::run_kinema({"eval", kinema_test::sample("problem_4_4_six_bar.toml")});
  REQUIRE(result.exit_status == 0);
  CHECK(readme.find("```\n$ ./build/kinema eval samples/problem_4_4_six_bar.toml\n" + result.out + "```") !=
        std::string::npos);
}
