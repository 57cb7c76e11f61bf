// The README says what is true: its library example is examples/library_usage.cpp
// as it is (that file is built against an installed kinema and run by the
// "package: ..." test), and the folders its "How it works" names exist.
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
