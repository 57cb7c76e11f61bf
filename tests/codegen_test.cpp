// The generated header compiles with -Wall -Wextra -Werror and gives the
// engine's numbers, for every sample.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <kinema/engine/model.hpp>
#include "test_support.hpp"

using kinema_test::read_file;

TEST_CASE("kinema codegen: the standalone header matches the engine for every sample") {
  const auto directory = std::filesystem::temp_directory_path() / "kinema_tests" / "codegen";
  std::filesystem::create_directories(directory);
  for (const char* sample : {"four_bar.toml", "slider_crank.toml", "piston_driven_crank.toml",
                             "example_4_1_r_trr.toml", "example_4_2_r_rtr_rrt.toml",
                             "problem_4_4_six_bar.toml", "problem_3_22_six_bar_sliders.toml"}) {
    const std::string sample_name = sample;
    CAPTURE(sample_name);
    const std::string name = std::string(sample).substr(0, std::string(sample).find('.'));
    const std::string header = (directory / (name + ".hpp")).string();
    const auto generated = kinema_test::run_kinema({"codegen", kinema_test::sample(sample), "-o", header});
    REQUIRE(generated.exit_status == 0);

    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const auto& input = model.system.input;
    const double step = input.dimension == kinema::Dimension::angle ? M_PI / 180 : 0.001;
    std::vector<double> inputs;
    for (int i = 0; i < 5; ++i) inputs.push_back(input.values.at(0) + i * step);

    // A driver that walks the same input values, warm-starting each from the last.
    std::ostringstream driver;
    driver.precision(17);  // the driver must see the same numbers as the engine
    driver << "#include \"" << header << "\"\n#include <cstdio>\nint main() {\n"
           << "  " << name << "::Parameters p;\n  double q[" << name << "::unknown_count];\n"
           << "  " << name << "::initial_guess(q);\n  " << name << "::Motion m;\n"
           << "  const double inputs[] = {";
    for (double v : inputs) driver << v << ", ";
    driver << "};\n  for (double x : inputs) {\n"
           << "    if (!" << name << "::evaluate(p, x, " << input.rate_value << ", " << input.second_rate_value
           << ", q, m)) return 1;\n"
           << "    for (int i = 0; i < " << name << "::unknown_count; ++i)\n"
           << "      std::printf(\"%.17g %.17g %.17g\\n\", m.q[i], m.qd[i], m.qdd[i]);\n"
           << "    for (int k = 0; k < " << name << "::point_count; ++k)\n"
           << "      for (int c = 0; c < 6; ++c) std::printf(\"%.17g\\n\", m.points[k][c]);\n"
           << "  }\n  return 0;\n}\n";
    const std::string source = (directory / (name + "_driver.cpp")).string();
    const std::string program = (directory / (name + "_driver")).string();
    std::ofstream(source) << driver.str();
    const std::string compile = std::string(KINEMA_CXX) + " -std=c++17 -O2 -Wall -Wextra -Werror -o '" +
                                program + "' '" + source + "' 2> '" + program + ".log'";
    const int compiled = std::system(compile.c_str());
    INFO(read_file(program + ".log"));
    REQUIRE(compiled == 0);
    REQUIRE(std::system(("'" + program + "' > '" + program + ".out'").c_str()) == 0);

    const auto states = kinema::analyse(model, inputs, kinema_test::with_rates(input.rate_value, input.second_rate_value));
    std::istringstream numbers(read_file(program + ".out"));
    auto close = [](double a, double b) { return std::fabs(a - b) <= 1e-9 * (1 + std::fabs(b)); };
    for (const auto& s : states) {
      REQUIRE(s.status == kinema::Status::ok);
      for (Eigen::Index i = 0; i < s.q.size(); ++i) {
        double q = 0, qd = 0, qdd = 0;
        numbers >> q >> qd >> qdd;
        CHECK(close(q, s.q[i]));
        CHECK(close(qd, s.qd[i]));
        CHECK(close(qdd, s.qdd[i]));
      }
      for (const auto& point : s.points) {
        for (double expected : {point.position[0], point.position[1], point.velocity[0], point.velocity[1],
                                 point.acceleration[0], point.acceleration[1]}) {
          double value = 0;
          numbers >> value;
          CHECK(close(value, expected));
        }
      }
    }
    CHECK(numbers.good());
  }
}
