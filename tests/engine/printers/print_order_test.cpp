// engine/printers: the same file prints the same formulas from every build. GiNaC
// orders the operands of sums and products by hashes that include addresses (of type
// information, which move from one build to the next) and symbol serial numbers; a
// printer that followed GiNaC's order printed `a*exp(I*theta2)` from one build and
// `exp(I*theta2)*a` from another. Inside one process the serials are what moves: a
// sample loaded again after other symbols were made is ordered otherwise by GiNaC, and
// every printer must print it byte for byte as before.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/model.hpp"
#include "engine/printers/printer.hpp"
#include "readers/mechanism_file.hpp"
#include "tests/test_support.hpp"

using kinema::PrintKind;

namespace {

// The derivation (text and LaTeX; the loops' equations and the seeds' two methods), the
// worked solution and the exported C++ header, or the message a printer refuses with.
std::vector<std::string> printed(const kinema::Model& model, const kinema::MotionTable& values) {
  std::vector<std::string> outputs;
  const auto print = [&](PrintKind kind, const char* format, const kinema::PrintJob& job) {
    std::ostringstream out;
    try {
      kinema::print_view(*kinema::find_printer(kind, format), out, job);
    } catch (const std::exception& e) {
      out << "refused: " << e.what();
    }
    outputs.push_back(out.str());
  };
  print(PrintKind::derivation, "text", kinema::PrintJob{model});
  print(PrintKind::derivation, "latex", kinema::PrintJob{model});
  print(PrintKind::document, "latex", kinema::PrintJob{model, &values});
  print(PrintKind::code, "cpp", kinema::PrintJob{model});
  for (auto m : {kinema::DerivationMethod::relative_velocity, kinema::DerivationMethod::joint_coordinates}) {
    kinema::PrintJob job{model};
    job.method = m;
    print(PrintKind::derivation, "text", job);
    print(PrintKind::derivation, "latex", job);
  }
  return outputs;
}

}  // namespace

// Exported code (kinema codegen) too: the tape takes operands in an order of its own and
// works every difference out one way round, whichever way GiNaC wrote it.
TEST_CASE("engine/printers: every sample prints the same formulas whatever GiNaC's order") {
  for (const char* sample : kinema_test::kSamples) {
    const std::string name = sample;
    CAPTURE(name);
    const std::string path = std::string(KINEMA_SAMPLES_DIR) + "/" + sample;
    const kinema::Mechanism mechanism = kinema::read_mechanism_file(path);
    const kinema::Model first = kinema::make_model(mechanism);
    // Numbers from one model for both: only the formulas are compared.
    const kinema::MotionTable values = kinema::solve_motion(
        first, {mechanism.input.values.empty() ? 0.0 : mechanism.input.values.front()});  // chains: time 0
    const std::vector<std::string> expected = printed(first, values);
    for (const int others : {1, 37, 500}) {
      CAPTURE(others);
      std::vector<GiNaC::symbol> shift(static_cast<std::size_t>(others));  // moves the serials of what follows
      const kinema::Model again = kinema::make_model(mechanism);
      const std::vector<std::string> outputs = printed(again, values);
      REQUIRE(outputs.size() == expected.size());
      for (std::size_t k = 0; k < outputs.size(); ++k) {
        CAPTURE(k);
        if (outputs[k] == expected[k]) continue;
        // The first line that differs, to say where.
        std::istringstream a(expected[k]), b(outputs[k]);
        std::string line_a, line_b;
        while (std::getline(a, line_a) && std::getline(b, line_b) && line_a == line_b) {
        }
        CHECK(line_b == line_a);
      }
    }
  }
}
