// The web page's JavaScript tape runner is generated from the tape's one op table: each
// operation written once, and run in node it gives what CompiledExpressions gives.
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/numeric/tape.hpp"
#include "engine/printers/code/tape_emitter.hpp"
#include "test_support.hpp"

using namespace GiNaC;
using Op = kinema::CompiledExpressions::Op;

namespace {

std::vector<std::string> table_names() {
  std::vector<std::string> names;
#define KINEMA_OP_NAME(name, operands, value, text, js) names.push_back(#name);
  KINEMA_TAPE_OPS(KINEMA_OP_NAME)
#undef KINEMA_OP_NAME
  names.push_back("sincos");
  return names;
}

std::size_t occurrences(const std::string& text, const std::string& word) {
  std::size_t count = 0;
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++count;
  return count;
}

}  // namespace

TEST_CASE("the page's tape runner has one case for each operation of the op table, numbered as the tape numbers it") {
  std::ostringstream runner;
  kinema::write_tape_runner_js(runner);
  const std::vector<std::string> names = table_names();
  for (std::size_t k = 0; k < names.size(); ++k) {
    CAPTURE(names[k]);
    CHECK(occurrences(runner.str(), "case " + std::to_string(k) + ": ") == 1);
    CHECK(occurrences(runner.str(), "break;  // " + names[k] + "\n") == 1);
  }
  CHECK(occurrences(runner.str(), "case ") == names.size());
}

TEST_CASE("the page's tape runner, run in node, gives CompiledExpressions' values for every operation") {
  const kinema_test::CommandResult node = kinema_test::run_shell("command -v node || command -v nodejs");
  if (node.exit_status != 0) {
    MESSAGE("node is not installed (Debian's nodejs): the runner is not run");
    return;
  }
  realsymbol a("a"), b("b"), c("c"), x("x");
  // Each operation of the table, and sincos, at least once (checked below); the fused ones
  // each with a product of their own (a shared product is not fused).
  const std::vector<ex> outputs = {a + b, a - b, a * b, a / b, -x, pow(a, 2) + b, pow(a, -3) + b, pow(a, b),
                                   tan(a), exp(b), log(a), sqrt(a), abs(x - a), atan2(a, b), asin(x), acos(x),
                                   atan(x), b * c + a, a * c - x, b - c * x, exp(x) - a * x, log(b) - pow(a, 2) * c,
                                   sin(a) * cos(a) + b};
  const kinema::CompiledExpressions tape({a, b, c, x}, outputs);
  std::vector<bool> used(table_names().size(), false);
  for (const auto& in : tape.instructions()) used[static_cast<std::size_t>(in.op)] = true;
  for (std::size_t k = 0; k < used.size(); ++k) {
    CAPTURE(table_names()[k]);
    CHECK(used[k]);
  }
  // Random inputs in each function's domain; the tape's values here and in node.
  std::mt19937 random(35);
  std::uniform_real_distribution<double> positive(0.2, 3.0), unit(-0.9, 0.9);
  nlohmann::json cases = nlohmann::json::array(), expected = nlohmann::json::array();
  std::vector<double> workspace = tape.make_workspace(), values(tape.output_count());
  for (int k = 0; k < 50; ++k) {
    const double inputs[4] = {positive(random), positive(random), positive(random), unit(random)};
    tape.evaluate(inputs, values.data(), workspace);
    cases.push_back(std::vector<double>(inputs, inputs + 4));
    expected.push_back(values);
  }
  nlohmann::json code = nlohmann::json::array(), registers = tape.initial_registers(), out = nlohmann::json::array();
  for (const auto& in : tape.instructions())
    for (const long long v : {static_cast<long long>(in.op), static_cast<long long>(in.out), static_cast<long long>(in.a),
                              static_cast<long long>(in.b), static_cast<long long>(in.c), static_cast<long long>(in.exponent)})
      code.push_back(v);
  for (std::size_t k = 0; k < tape.output_count(); ++k) out.push_back(tape.output_register(0, k));
  std::ostringstream script;
  kinema::write_tape_runner_js(script);
  script << "const code = " << code.dump() << ", initial = " << registers.dump() << ", outputs = " << out.dump()
         << ", cases = " << cases.dump() << ";\n"
         << "const pick = (k) => Int32Array.from(code.filter((v, i) => i % 6 === k));\n"
            "const tape = { op: pick(0), out: pick(1), a: pick(2), b: pick(3), c: pick(4), e: pick(5) };\n"
            "console.log(JSON.stringify(cases.map((inputs) => {\n"
            "  const r = Float64Array.from(initial);\n"
            "  inputs.forEach((v, i) => { r[i] = v; });\n"
            "  kinemaTapeRunner.run(tape, r, 0, tape.op.length);\n"
            "  return outputs.map((k) => r[k]);\n"
            "})));\n";
  const std::string path = kinema_test::write_temporary("tape_runner_test.js", script.str());
  const kinema_test::CommandResult run = kinema_test::run_shell("node " + kinema_test::shell_quote(path));
  REQUIRE(run.exit_status == 0);
  const nlohmann::json got = nlohmann::json::parse(run.out);
  REQUIRE(got.size() == expected.size());
  for (std::size_t k = 0; k < got.size(); ++k)
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const double want = expected[k][i], have = got[k][i];
      CAPTURE(outputs[i]);
      CHECK(std::fabs(have - want) <= 1e-14 * std::max(1.0, std::fabs(want)));
    }
}
