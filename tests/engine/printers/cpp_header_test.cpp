// The generated header compiles with -Wall -Wextra -Werror, gives the engine's
// numbers, and calls the same positions singular as the engine, for every sample.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "engine/model.hpp"
#include "engine/numeric/solver.hpp"
#include "engine/printers/code/cpp_header.hpp"
#include "tests/test_support.hpp"

using kinema_test::read_file;

namespace {

using kinema_test::kSamples;  // every bundled sample

/// A sample's sweep (SI): a revolution in 1 deg steps from the file's first value
/// for a crank; for a slider, the file's value +- the length scale on a whole-mm
/// grid (exact decimal values, so dead centres at whole millimetres are hit exactly:
/// the piston-driven crank's at 100 and 200 mm).
std::vector<double> sweep_of(const kinema::Model& model) {
  const auto& input = model.system.input;
  const double first = input.values.at(0);
  std::vector<double> inputs;
  if (input.dimension == kinema::Dimension::angle) {
    for (int degree = 0; degree <= 360; ++degree) inputs.push_back(first + degree * M_PI / 180);
  } else {
    const double reach = model.kinematics.length_scale();
    for (long mm = std::lround(std::floor((first - reach) * 1000)); mm <= std::lround(std::ceil((first + reach) * 1000));
         ++mm)
      inputs.push_back(static_cast<double>(mm) / 1000.0);
  }
  return inputs;
}

/// A program for header NAME that reads from stdin: a count and that many input
/// values, walked from initial_guess with each warm-started from the last (as a
/// user would); then a count and that many rows "theta q...", each evaluated
/// from that q. Per value it prints the status (0 ok, 1 singular, 2 unassembled),
/// the reciprocal condition, q, qd, qdd, the points' values and the frames'.
std::string driver_source(const std::string& header, const std::string& name) {
  std::ostringstream d;
  d << "#include \"" << header << "\"\n#include <cstdio>\n"
    << "namespace {\n"
    << "void print(" << name << "::Status status, const " << name << "::Motion& m) {\n"
    << "  std::printf(\"%d %.17g\", static_cast<int>(status), m.reciprocal_condition);\n"
    << "  for (int i = 0; i < " << name << "::unknown_count; ++i)\n"
    << "    std::printf(\" %.17g %.17g %.17g\", m.q[i], m.qd[i], m.qdd[i]);\n"
    << "  for (int k = 0; k < " << name << "::point_count; ++k)\n"
    << "    for (double value : m.points[k]) std::printf(\" %.17g\", value);\n"
    << "  for (int k = 0; k < " << name << "::frame_count; ++k)\n"
    << "    for (double value : m.frames[k]) std::printf(\" %.17g\", value);\n"
    << "  std::printf(\"\\n\");\n"
    << "}\n"
    << "}  // namespace\n"
    << "int main() {\n"
    << "  const " << name << "::Parameters p;\n"
    << "  double rate = 0, second_rate = 0, theta = 0, q[" << name << "::unknown_count];\n"
    << "  " << name << "::Motion m;\n"
    << "  int count = 0;\n"
    << "  if (std::scanf(\"%lf %lf %d\", &rate, &second_rate, &count) != 3) return 1;\n"
    << "  " << name << "::initial_guess(q);\n"
    << "  for (int k = 0; k < count; ++k) {\n"
    << "    if (std::scanf(\"%lf\", &theta) != 1) return 1;\n"
    << "    print(" << name << "::evaluate(p, theta, rate, second_rate, q, m), m);\n"
    << "  }\n"
    << "  if (std::scanf(\"%d\", &count) != 1) return 1;\n"
    << "  for (int k = 0; k < count; ++k) {\n"
    << "    if (std::scanf(\"%lf\", &theta) != 1) return 1;\n"
    << "    for (double& value : q)\n"
    << "      if (std::scanf(\"%lf\", &value) != 1) return 1;\n"
    << "    print(" << name << "::evaluate(p, theta, rate, second_rate, q, m), m);\n"
    << "  }\n"
    << "  return 0;\n"
    << "}\n";
  return d.str();
}

/// One line of the driver's output.
struct HeaderResult {
  int status = -1;
  double reciprocal_condition = 0;
  std::vector<double> q, qd, qdd, points;
};

/// The next number of the driver's output ("nan" included, which >> does not read).
double next_number(std::istream& in) {
  std::string word;
  in >> word;
  return word.empty() ? -1.0 : std::strtod(word.c_str(), nullptr);
}

HeaderResult read_result(std::istream& in, std::size_t n, std::size_t point_values) {
  HeaderResult r;
  r.status = static_cast<int>(next_number(in));
  r.reciprocal_condition = next_number(in);
  r.q.resize(n);
  r.qd.resize(n);
  r.qdd.resize(n);
  r.points.resize(point_values);
  for (std::size_t i = 0; i < n; ++i) {
    r.q[i] = next_number(in);
    r.qd[i] = next_number(in);
    r.qdd[i] = next_number(in);
  }
  for (double& value : r.points) value = next_number(in);
  return r;
}

/// a and b agree to `relative` (b's size, or 1 if it is smaller).
bool agree(double a, double b, double relative) { return std::fabs(a - b) <= relative * (1 + std::fabs(b)); }

/// The header's numbers at an ok position are the engine's: the same code on the
/// same values but for the rounding of the tape, which the rates and second rates
/// amplify near a singular position (by up to 1 / reciprocal condition).
void check_numbers(const HeaderResult& header, const kinema::MotionState& s) {
  const double relative = 1e-9 / std::min(1.0, s.reciprocal_condition);
  auto close = [relative](double a, double b) { return agree(a, b, relative); };
  for (Eigen::Index i = 0; i < s.q.size(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    CHECK(close(header.q[k], s.q[i]));
    CHECK(close(header.qd[k], s.qd[i]));
    CHECK(close(header.qdd[k], s.qdd[i]));
  }
  std::size_t k = 0;
  for (const auto& point : s.points) {
    for (const auto* part : {&point.position, &point.velocity, &point.acceleration})
      for (std::size_t c = 0; c < point.dimension; ++c, ++k) {
        INFO("point value " << k << ": header " << header.points.at(k) << ", engine " << (*part)[c]);
        CHECK(close(header.points.at(k), (*part)[c]));
      }
  }
  for (const auto& frame : s.frames) {
    for (const auto* part : {&frame.angular_velocity, &frame.angular_acceleration})
      for (std::size_t c = 0; c < 3; ++c, ++k) {
        INFO("frame value " << k << ": header " << header.points.at(k) << ", engine " << (*part)[c]);
        CHECK(close(header.points.at(k), (*part)[c]));
      }
  }
  CHECK(k == header.points.size());
}

const char* status_name(int status) {
  return status == 0 ? "ok" : status == 1 ? "singular" : status == 2 ? "unassembled" : "(no output)";
}

}  // namespace

TEST_CASE("kinema codegen: the header's numbers and singular positions are the engine's, for every sample") {
  const auto directory = kinema_test::scratch_directory() / "codegen";
  std::filesystem::create_directories(directory);
  std::size_t piston_singular = 0;
  for (const char* sample : kSamples) {
    const std::string sample_name = sample;
    CAPTURE(sample_name);
    const std::string name = sample_name.substr(0, sample_name.find('.'));
    const std::string header = (directory / (name + ".hpp")).string();
    const auto generated = kinema_test::run_kinema({"codegen", kinema_test::sample(sample), "-o", header});
    REQUIRE(generated.exit_status == 0);

    const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
    const auto& input = model.system.input;
    const std::size_t n = model.kinematics.unknown_count();
    const std::size_t point_values = model.kinematics.layout().observable_output_count();  // points, frames
    const auto options = kinema_test::with_rates(input.rate_value, input.second_rate_value);

    // The first five values 1 deg (1 mm) apart, walked from the guesses.
    const double step = input.dimension == kinema::Dimension::angle ? M_PI / 180 : 0.001;
    std::vector<double> walk;
    for (int i = 0; i < 5; ++i) walk.push_back(input.values.at(0) + i * step);
    const auto walked = kinema::solve_motion(model, walk, options);
    // The sweep, by the engine; the header is then run at each assembled position from
    // the engine's q (Newton converges at once), so both judge the same position.
    // Around each singular position it finds, the sweep is refined (10^-2 to 10^-13
    // of the length scale or a radian away), through where the pivots stop deciding
    // and where the singular values cross the threshold.
    std::vector<double> inputs = sweep_of(model);
    {
      const auto first_run = kinema::solve_motion(model, inputs, options);
      const double unit = input.dimension == kinema::Dimension::angle ? 1.0 : model.kinematics.length_scale();
      for (std::size_t row = 0; row < first_run.size(); ++row) {
        if (first_run.status(row) != kinema::Status::singular) continue;
        for (int k = 2; k <= 13; ++k)
          for (double side : {-1.0, 1.0}) inputs.push_back(first_run.input(row) + side * unit * std::pow(10.0, -k));
      }
      std::sort(inputs.begin(), inputs.end());
    }
    const auto swept = kinema::solve_motion(model, inputs, options);

    std::ostringstream stdin_text;
    stdin_text.precision(17);  // the driver must see the same numbers as the engine
    stdin_text << input.rate_value << " " << input.second_rate_value << " " << walk.size() << "\n";
    for (double v : walk) stdin_text << v << "\n";
    std::vector<std::size_t> assembled;
    for (std::size_t row = 0; row < swept.size(); ++row)
      if (swept.status(row) != kinema::Status::unassembled) assembled.push_back(row);
    stdin_text << assembled.size() << "\n";
    for (std::size_t row : assembled) {
      stdin_text << swept.input(row);
      const auto q = swept.q(row);
      for (Eigen::Index i = 0; i < q.size(); ++i) stdin_text << " " << q[i];
      stdin_text << "\n";
    }

    // One driver per sample, compiled once.
    const std::string source = (directory / (name + "_driver.cpp")).string();
    const std::string program = (directory / (name + "_driver")).string();
    std::ofstream(source) << driver_source(header, name);
    std::ofstream(program + ".in") << stdin_text.str();
    const std::string compile = std::string(KINEMA_CXX) + " -std=c++17 -O2 -Wall -Wextra -Werror -o '" +
                                program + "' '" + source + "' 2> '" + program + ".log'";
    const int compiled = std::system(compile.c_str());
    INFO(read_file(program + ".log"));
    REQUIRE(compiled == 0);
    REQUIRE(std::system(("'" + program + "' < '" + program + ".in' > '" + program + ".out'").c_str()) == 0);
    std::istringstream out(read_file(program + ".out"));

    for (const auto& s : walked) {
      REQUIRE(s.status == kinema::Status::ok);
      const HeaderResult header_result = read_result(out, n, point_values);
      REQUIRE(header_result.status == 0);
      check_numbers(header_result, s);
    }

    std::size_t singular = 0, ok = 0;
    double least_ok = INFINITY, most_singular = 0;
    for (std::size_t row : assembled) {
      const kinema::MotionState s = swept[row];
      const HeaderResult header_result = read_result(out, n, point_values);
      const std::string engine_status = s.status == kinema::Status::ok ? "ok" : "singular";
      const std::string header_status = status_name(header_result.status);
      INFO("input " << s.input << ": engine " << engine_status << " (reciprocal condition "
                    << s.reciprocal_condition << "), header " << header_status << " ("
                    << header_result.reciprocal_condition << ")");
      REQUIRE(header_status == engine_status);
      // The same matrix, the same code: the same measure (to the rounding of the tape).
      CHECK(std::fabs(header_result.reciprocal_condition - s.reciprocal_condition) <=
            1e-12 + 1e-9 * s.reciprocal_condition);
      if (s.status == kinema::Status::ok) {
        ++ok;
        least_ok = std::min(least_ok, s.reciprocal_condition);
        check_numbers(header_result, s);
      } else {
        ++singular;
        most_singular = std::max(most_singular, s.reciprocal_condition);
      }
    }
    CHECK(out.good());
    INFO(inputs.size() << " values, " << ok << " ok, " << singular << " singular, "
                       << inputs.size() - assembled.size() << " unassembled; reciprocal condition down to "
                       << least_ok << " where ok, up to " << most_singular << " where singular");
    CHECK(ok > 0);
    if (sample_name == "piston_driven_crank.toml") {
      // Its dead centres, x = b - a and a + b, are in the sweep, hit exactly: singular.
      for (double dead_centre : {0.1, 0.2}) {
        CAPTURE(dead_centre);
        const auto row = std::find(inputs.begin(), inputs.end(), dead_centre) - inputs.begin();
        REQUIRE(row < static_cast<std::ptrdiff_t>(inputs.size()));
        CHECK(swept.status(static_cast<std::size_t>(row)) == kinema::Status::singular);
      }
      piston_singular = singular;
    }
  }
  // So the comparison above did meet singular positions.
  CHECK(piston_singular >= 2);
}

TEST_CASE("solver::reciprocal_condition: the pivot ratio where clearly regular, else the singular values - 1 x 1 against the length scale") {
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t n = 1 + static_cast<std::size_t>(trial) % 6;
    const auto size = static_cast<Eigen::Index>(n);
    Eigen::MatrixXd m(size, size);
    for (Eigen::Index i = 0; i < size; ++i)
      for (Eigen::Index j = 0; j < size; ++j) m(i, j) = normal(random);
    if (n > 1 && trial % 2 == 0) {
      // Nearly singular: the smallest singular value pulled down to 10^-k of the largest.
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Eigen::VectorXd sigma = svd.singularValues();
      sigma[size - 1] = sigma[0] * std::pow(10.0, -(trial % 15));
      m = svd.matrixU() * sigma.asDiagonal() * svd.matrixV().transpose();
    }
    std::vector<double> row_major(n * n), lu(n * n);
    std::vector<std::size_t> pivots(n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j)
        row_major[i * n + j] = m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    lu = row_major;
    kinema::solver::lu_factor(lu.data(), pivots.data(), n);
    const double length_scale = 0.5;  // what a 1 x 1 pivot is compared with
    const double pivots_say = kinema::solver::pivot_ratio(lu.data(), n, length_scale);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m);
    const Eigen::VectorXd& s = svd.singularValues();
    const double singular_values_say = s[size - 1] / s[0];
    std::vector<double> scratch = row_major;
    CHECK(std::fabs(kinema::solver::singular_value_ratio(scratch.data(), n) - singular_values_say) <= 1e-14);
    scratch = row_major;
    const double measure = kinema::solver::reciprocal_condition(lu.data(), scratch.data(), n, length_scale);
    if (n == 1) {  // no other pivot: |a| against the length scale, at most 1
      CHECK(measure == std::min(1.0, std::fabs(m(0, 0)) / length_scale));
    } else if (pivots_say >= kinema::solver::kClearlyRegularPivotRatio) {
      CHECK(measure == pivots_say);
    } else {
      CHECK(std::fabs(measure - singular_values_say) <= 1e-14);
    }

    // The least-squares step agrees with Eigen's complete orthogonal decomposition.
    if (singular_values_say > 1e-8) {
      Eigen::VectorXd b(size);
      for (Eigen::Index i = 0; i < size; ++i) b[i] = normal(random);
      const Eigen::VectorXd expected = m.completeOrthogonalDecomposition().solve(b);
      std::vector<double> v(n * n), x(n);
      scratch = row_major;
      kinema::solver::least_squares_solve(scratch.data(), v.data(), b.data(), x.data(), n);
      const Eigen::VectorXd got = Eigen::Map<const Eigen::VectorXd>(x.data(), size);
      CHECK((got - expected).norm() <= 1e-12 * expected.norm() / singular_values_say);
    }
  }
  // Exactly singular and the identity.
  double singular[] = {1, 2, 2, 4}, identity[] = {1, 0, 0, 1};
  CHECK(kinema::solver::singular_value_ratio(singular, 2) <= 1e-15);
  CHECK(kinema::solver::singular_value_ratio(identity, 2) == 1.0);
}

namespace {

// The four-bar with its parameters a, b, c, d named `names` (in the loop and P too), and
// its header generated by kinema into directory/header_name.
struct RenamedHeader {
  std::filesystem::path directory;
  std::string mechanism, header, code;
};
RenamedHeader four_bar_header_named(const std::string& case_name, const std::array<std::string, 4>& names,
                                    const std::string& header_name) {
  RenamedHeader made;
  made.directory = kinema_test::scratch_directory() / case_name;
  std::filesystem::create_directories(made.directory);
  std::string text = kinema_test::four_bar_text();
  for (std::size_t k = 0; k < 4; ++k) text = kinema_test::replaced(std::string(1, "abcd"[k]) + " = ", names[k] + " = ", text);
  text = kinema_test::replaced("\"a*exp(I*theta2) + b*exp(I*theta3) - c*exp(I*theta4) - d\"",
                               "\"" + names[0] + "*exp(I*theta2) + " + names[1] + "*exp(I*theta3) - " + names[2] +
                                   "*exp(I*theta4) - " + names[3] + "\"",
                               text);
  text = kinema_test::replaced("P = \"a*exp(I*theta2)\"", "P = \"" + names[0] + "*exp(I*theta2)\"", text);
  made.mechanism = kinema_test::write_temporary(case_name + ".toml", text);
  made.header = (made.directory / header_name).string();
  const auto generated = kinema_test::run_kinema({"codegen", made.mechanism, "-o", made.header});
  INFO(generated.err);
  REQUIRE(generated.exit_status == 0);
  made.code = read_file(made.header);
  return made;
}

// A program that includes `includes`, then the header, and evaluates the four-bar with
// namespace `name`: compiled with g++ -Werror in `standard`, it builds and runs.
void check_driver_runs(const RenamedHeader& made, const std::string& name, const std::string& includes,
                       const std::string& standard) {
  const std::string source = (made.directory / "driver.cpp").string();
  std::ofstream(source) << includes << "#include \"" << made.header << "\"\nint main() {\n  " << name
                        << "::Parameters p;\n  double q[" << name << "::unknown_count];\n  " << name
                        << "::initial_guess(q);\n  " << name << "::Motion m;\n  return " << name
                        << "::evaluate(p, 0.7, 10, 0, q, m) == " << name << "::Status::ok ? 0 : 1;\n}\n";
  const std::string program = (made.directory / "driver").string();
  const int compiled = std::system((std::string(KINEMA_CXX) + " -std=" + standard + " -Wall -Wextra -Werror -o '" +
                                    program + "' '" + source + "' 2> '" + program + ".log'").c_str());
  INFO(read_file(program + ".log"));
  CHECK(compiled == 0);
  CHECK(std::system(("'" + program + "'").c_str()) == 0);
}

}  // namespace

// Issue 9, finding 18: names that are C++ keywords or <cmath> macros, and a header
// named int.hpp, still give a header that compiles (names get a trailing _).
TEST_CASE("kinema codegen: keyword and macro names are renamed, the header compiles - --namespace int is refused") {
  const RenamedHeader made = four_bar_header_named("codegen_keywords", {"int", "M_PI", "NAN", "or"}, "int.hpp");
  CHECK(made.code.find("namespace int_ {") != std::string::npos);
  CHECK(made.code.find("double int_ = ") != std::string::npos);
  CHECK(made.code.find("double M_PI_ = ") != std::string::npos);
  check_driver_runs(made, "int_", "#include <cstdio>\n", "c++17");

  const auto refused = kinema_test::run_kinema({"codegen", made.mechanism, "-o", made.header, "--namespace", "int"});
  CHECK(refused.exit_status == 2);
  CHECK(refused.err.find("int_") != std::string::npos);
}

// Session 30's hostile-input review: g++'s GNU dialect (its default) predefines linux
// and unix, and a program may include <cfloat> and <climits> first (DBL_MAX,
// CHAR_BIT); a header named std.hpp or été.hpp gave namespace std or __t__ (reserved).
TEST_CASE("kinema codegen: macro names of g++ and the C headers, and reserved namespaces, are renamed") {
  CHECK(kinema::cpp_identifier("std") == "std_");
  CHECK(kinema::cpp_identifier("\xc3\xa9t\xc3\xa9") == "mechanism_t_");
  CHECK(kinema::cpp_identifier("a__b") == "a_b");
  CHECK(kinema::cpp_identifier("_x") == "mechanism_x");
  CHECK(kinema::cpp_identifier("SIGMA") == "SIGMA_");  // SIG...: <csignal>'s family
  CHECK(kinema::cpp_identifier("Sigma") == "Sigma");
  CHECK(kinema::cpp_identifier("four-bar") == "four_bar");

  const RenamedHeader made = four_bar_header_named("codegen_macros", {"linux", "DBL_MAX", "unix", "CHAR_BIT"}, "linux.hpp");
  CHECK(made.code.find("namespace linux_ {") != std::string::npos);
  CHECK(made.code.find("double DBL_MAX_ = ") != std::string::npos);
  check_driver_runs(made, "linux_", "#include <cfloat>\n#include <climits>\n#include <cstdio>\n", "gnu++17");
}

// Audit 2026-11-24 (tests/fuzz/regressions/codegen_bidi_title.toml): U+202E in a title went
// into a // comment and g++ -Werror refused the header (-Wbidi-chars). A file's text is
// refused now (tests/cli/bad_input_test.cpp); what is left, a multi-line title and a path
// from the command line with a line break and U+202E, goes into the comments on one line.
TEST_CASE("kinema codegen: a multi-line title and a path with a line break and U+202E give a header that compiles") {
  const auto directory = kinema_test::scratch_directory() / "codegen_text";
  std::filesystem::create_directories(directory);
  const std::string mechanism = (directory / "four\xe2\x80\xae\nbar.toml").string();
  std::ofstream(mechanism) << kinema_test::replaced("title = \"four-bar\"",
                                                    "title = \"\"\"four-bar\nopen branch \\\\\"\"\"\n"
                                                    "description = \"\"\"two\nlines\"\"\"");
  const std::string header = (directory / "text.hpp").string();
  const auto generated = kinema_test::run_kinema({"codegen", mechanism, "-o", header});
  INFO(generated.err);
  REQUIRE(generated.exit_status == 0);
  const std::string code = read_file(header);
  CHECK(code.find("\xe2\x80\xae") == std::string::npos);
  CHECK(code.find("four[U+202E] bar.toml: four-bar open branch \\.") != std::string::npos);
  const std::string source = (directory / "include.cpp").string();
  std::ofstream(source) << "#include \"" << header << "\"\nint main() { return text::unknown_count == 2 ? 0 : 1; }\n";
  const std::string program = (directory / "include").string();
  const int compiled = std::system((std::string(KINEMA_CXX) + " -std=c++17 -Wall -Wextra -Werror -o '" + program +
                                    "' '" + source + "' 2> '" + program + ".log'").c_str());
  INFO(read_file(program + ".log"));
  CHECK(compiled == 0);
}

// Issue 33: two of the file's names that map to one C++ name were duplicate members, and
// the macros of the C library beyond the families (math_errhandling, M_PIl, WNOHANG,
// EINVAL, P_tmpdir, PATH_MAX, ...) gave headers that did not compile after <cerrno>,
// <cstdio>, <climits>, <cmath>. Each compiles alone and after them.
TEST_CASE("kinema codegen: names that map to one C++ name are numbered, every C library macro is renamed") {
  CHECK(kinema::cpp_identifiers({"int", "int_", "a_b", "a__b", "Parameters"}, {"Parameters"}) ==
        std::vector<std::string>{"int_", "int_2", "a_b", "a_b_2", "Parameters_2"});
  const std::string after = "#include <cerrno>\n#include <cstdio>\n#include <climits>\n#include <cmath>\n";
  struct Case {
    std::array<std::string, 4> names;
    std::string header, members;
  };
  for (const Case& c : std::vector<Case>{
           {{"int", "int_", "a_b", "a__b"}, "math_errhandling.hpp", "int_ int_2 a_b a_b_2"},
           {{"M_PIl", "M_El", "FD_SETSIZE", "WNOHANG"}, "EINVAL.hpp", "M_PIl_ M_El_ FD_SETSIZE_ WNOHANG_"},
           {{"ENOENT", "P_tmpdir", "PATH_MAX", "L_ctermid"}, "M_El.hpp", "ENOENT_ P_tmpdir_ PATH_MAX_ L_ctermid_"}}) {
    CAPTURE(c.header);
    const RenamedHeader made = four_bar_header_named("codegen_" + c.header.substr(0, c.header.find('.')), c.names, c.header);
    std::istringstream members(c.members);
    for (std::string member; members >> member;) {
      CAPTURE(member);
      CHECK(made.code.find("  double " + member + " = ") != std::string::npos);
    }
    const std::string space = c.header.substr(0, c.header.find('.')) + "_";
    CHECK(made.code.find("namespace " + space + " {") != std::string::npos);
    check_driver_runs(made, space, "", "gnu++17");
    check_driver_runs(made, space, after, "gnu++17");
  }
  for (const char* name : {"math_errhandling", "M_PIl", "FD_SETSIZE", "WNOHANG", "EINVAL", "P_tmpdir", "PATH_MAX"}) {
    CAPTURE(name);
    const auto refused = kinema_test::run_kinema({"codegen", kinema_test::sample("four_bar.toml"), "-o",
                                                  kinema_test::fresh_directory("codegen_namespace") + "/x.hpp",
                                                  "--namespace", name});
    CHECK(refused.exit_status == 2);
    CHECK(refused.err.find(std::string("try \"") + name + "_\"") != std::string::npos);
  }
}

// The list of macros (engine/printers/code/c_library_macros.inc) is what this compiler and
// C library define: a macro missing from it would be a header that does not compile.
TEST_CASE("kinema codegen: every macro of the C and C++ library headers is a reserved name") {
  const auto listed = kinema_test::run_shell(
      "for h in cassert cctype cerrno cfenv cfloat cinttypes climits clocale cmath csetjmp csignal cstdarg cstddef "
      "cstdint cstdio cstdlib cstring ctime cuchar cwchar cwctype algorithm array atomic chrono complex "
      "condition_variable functional iostream limits memory mutex string thread vector; do echo \"#include <$h>\"; "
      "done | " + std::string(KINEMA_CXX) + " -std=gnu++17 -dM -E -x c++ - | awk '{print $2}' | sed 's/(.*//' | grep -v '^_' | sort -u");
  REQUIRE(listed.exit_status == 0);
  std::istringstream names(listed.out);
  std::size_t count = 0;
  for (std::string name; names >> name; ++count) {
    CAPTURE(name);
    CHECK(kinema::is_cpp_reserved(name));
  }
  CHECK(count > 500);
}

TEST_CASE("kinema codegen: the header's kernel is engine/numeric/solver.hpp's text, and it has no Newton or LU of its own") {
  const std::string source = read_file(std::string(KINEMA_SAMPLES_DIR) + "/../engine/numeric/solver.hpp");
  const std::string open = "\nnamespace kinema::solver {\n", close = "\n}  // namespace kinema::solver";
  const std::size_t from = source.find(open), to = source.find(close);
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  const std::string kernel = source.substr(from + open.size(), to - from - open.size());
  // The kernel holds the rules the header must not restate.
  for (const char* rule : {"inline bool newton(", "inline void newton_step(", "inline void lu_factor(",
                           "inline void lu_solve(", "inline void least_squares_solve("})
    CHECK(kernel.find(rule) != std::string::npos);
  const auto directory = kinema_test::scratch_directory() / "codegen_kernel";
  std::filesystem::create_directories(directory);
  for (const char* sample : {"four_bar.toml", "problem_4_4_joints.toml", "robot_arm_seed000.toml"}) {
    CAPTURE(sample);
    const std::string header = (directory / "header.hpp").string();
    REQUIRE(kinema_test::run_kinema({"codegen", kinema_test::sample(sample), "-o", header}).exit_status == 0);
    const std::string text = read_file(header);
    const std::size_t at = text.find(kernel);
    REQUIRE(at != std::string::npos);
    const std::string rest = text.substr(0, at) + text.substr(at + kernel.size());
    // Outside the pasted kernel: no iteration, halving, pivot search or row swap, and its
    // rules only called (solver::...).
    for (const char* own : {"kNewtonIterations", "kStepHalvings", "lambda", "std::swap", "std::fabs(a[",
                            "for (int iteration", "jacobi"}) {
      CAPTURE(own);
      CHECK(rest.find(own) == std::string::npos);
    }
    CHECK(rest.find("solver::newton(") != std::string::npos);
    CHECK(rest.find("solver::factorise(") != std::string::npos);
  }
}
