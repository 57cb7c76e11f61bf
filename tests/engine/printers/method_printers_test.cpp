// `derive --method` and `kinema latex --method`: the seeds' relative-velocity and
// joint-coordinate forms printed for every joints-and-links sample; the LaTeX compiles,
// and every formula it carries in a "% kinema:" comment reads back to the relation the
// engine derived (engine/symbolic/dyad_method, checked there by meaning).
#include <doctest/doctest.h>

#include <map>
#include <sstream>
#include <vector>

#include "engine/symbolic/dyad_method.hpp"
#include "engine/constraints/expression_parts.hpp"

#include "engine/printers/latex_pages.hpp"
#include "tests/test_support.hpp"

namespace {

const char* const kJointSamples[] = {"problem_4_4_joints.toml",      "example_4_1_joints.toml",
                                     "example_4_2_joints.toml",      "problem_3_22_joints.toml",
                                     "problem_4_1_parallelogram.toml", "problem_4_1_antiparallelogram.toml",
                                     "triple_rocker_circuit.toml"};

// Every "% kinema: name = formula" comment read back equals a solution the engine
// derived for that name (by meaning); returns how many were read.
std::size_t comments_read_back(const std::string& output, const kinema::Model& model, const kinema::DyadDerivation& d) {
  GiNaC::symtab table;
  const auto& system = model.system;
  for (const auto& p : system.parameters) table[p.symbol.get_name()] = p.symbol;
  for (const GiNaC::realsymbol& s : {system.input.symbol, system.input.rate, system.input.second_rate}) table[s.get_name()] = s;
  for (const auto& q : system.unknowns)
    for (const GiNaC::realsymbol& s : {q.symbol, q.rate, q.second_rate}) table[s.get_name()] = s;
  for (const auto& [name, symbol] : d.symbols) table[name] = symbol;
  std::multimap<std::string, GiNaC::ex> solutions;
  for (const auto& step : d.steps)
    for (const auto* list : {&step.velocity, &step.acceleration})
      for (const auto& r : *list)
        if (r.kind == kinema::MethodRelation::Kind::solution) solutions.insert({kinema::to_text(r.left), r.right});
  GiNaC::parser reader(table, true);
  std::istringstream lines(output);
  std::string line;
  std::size_t read = 0;
  while (std::getline(lines, line)) {
    const auto at = line.find("% kinema: ");
    if (at == std::string::npos) continue;
    const std::string formula = line.substr(at + 10);
    const auto equals = formula.find(" = ");
    const std::string name = formula.substr(0, equals);
    CAPTURE(line);
    const GiNaC::ex value = reader(formula.substr(equals + 3));
    bool found = false;
    const auto [first, last] = solutions.equal_range(name);
    for (auto it = first; it != last; ++it) found = found || GiNaC::normal(value - it->second).is_zero();
    CHECK(found);
    ++read;
  }
  return read;
}

}  // namespace

TEST_CASE("derive --method: the seeds' forms in text and LaTeX, for every joints-and-links sample") {
  // Two pdflatex runs for all: the derivations in one plain article, the documents' bodies
  // in one document, each starting a page at a label (its pages: to the next one's).
  std::string derivations = "\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n";
  std::string preamble, documents;
  std::vector<std::string> parts;
  for (const char* sample : kJointSamples) {
    for (const char* method : {"relative-velocity", "joint-coordinates"}) {
      CAPTURE(sample);
      CAPTURE(method);
      const kinema::Model model = kinema::load_model(kinema_test::sample(sample));
      const kinema::DyadDerivation d = kinema::derive_by_dyads(model.system, *kinema::find_method(method));
      const auto text = kinema_test::run_kinema({"derive", kinema_test::sample(sample), "--method", method});
      REQUIRE(text.exit_status == 0);
      CHECK(text.out.find(std::string("1. Velocities and accelerations, group by group (") + method + ")") != std::string::npos);
      CHECK(text.out.find("Jacobian") == std::string::npos);  // the loops' form is not repeated
      for (const auto& step : d.steps) CHECK(text.out.find("\n  " + step.heading + "\n") != std::string::npos);
      const auto latex = kinema_test::run_kinema({"derive", "--format", "latex", kinema_test::sample(sample), "--method", method});
      REQUIRE(latex.exit_status == 0);
      CHECK(comments_read_back(latex.out, model, d) >= 2 * model.system.unknowns.size());
      const std::string name = std::string(sample).substr(0, std::string(sample).find('.')) + "_" + method;
      parts.push_back(name);
      derivations += "\\clearpage\n% part " + name + "\n" + latex.out;
      const auto document = kinema_test::run_kinema({"latex", kinema_test::sample(sample), "--method", method});
      REQUIRE(document.exit_status == 0);
      const std::string title = std::string(method) == "relative-velocity" ? "relative velocities" : "joint coordinates";
      CHECK(document.out.find("\\subsection*{Velocity analysis by " + title + "}") != std::string::npos);
      CHECK(document.out.find("\\subsection*{Acceleration analysis by " + title + "}") != std::string::npos);
      CHECK(comments_read_back(document.out, model, d) >= 2 * model.system.unknowns.size());
      const std::size_t body = document.out.find("\\begin{document}") + 16;
      if (preamble.empty()) preamble = document.out.substr(0, body);
      CHECK(document.out.substr(0, body) == preamble);  // one preamble for all
      documents += "\\clearpage\\label{kinema-part-" + name + "}\n" +
                   document.out.substr(body, document.out.rfind("\\end{document}") - body);
    }
  }
  std::string log;
  CHECK(kinema_test::compile_document(derivations + "\\end{document}\n", "derive_methods", log) >= 1);
  const int pages = kinema_test::compile_document(preamble + documents + "\\end{document}\n", "documents_methods", log);
  INFO(log.substr(log.size() > 3000 ? log.size() - 3000 : 0));
  REQUIRE(pages > 0);
  std::map<std::string, int> starts = kinema_test::label_pages("documents_methods");
  for (std::size_t k = 0; k < parts.size(); ++k) {
    CAPTURE(parts[k]);
    const int end = k + 1 < parts.size() ? starts["kinema-part-" + parts[k + 1]] : pages + 1;
    CHECK(end - starts["kinema-part-" + parts[k]] >= 3);  // data and equations, results, plots
  }
}

TEST_CASE("derive --method: Problem 4.4's relative velocities are seed 004's equations") {
  const auto text = kinema_test::run_kinema({"derive", kinema_test::sample("problem_4_4_joints.toml"), "--method", "relative-velocity"});
  REQUIRE(text.exit_status == 0);
  for (const char* line : {"      v_B = omega1 x r_AB\n", "      v_C = v_B + omega2 x r_BC = omega3 x r_DC\n",
                           "      v_E = v_C + omega3 x r_CE\n", "      v_F = v_E + omega4 x r_EF = vF u_F5\n",
                           "      a_C = a_B + alpha2 x r_BC - omega2^2 r_BC = alpha3 x r_DC - omega3^2 r_DC\n"}) {
    CAPTURE(line);
    CHECK(text.out.find(line) != std::string::npos);
  }
}

TEST_CASE("derive --method on vector loops, or an unknown method, is refused") {
  const auto loops = kinema_test::run_kinema({"derive", kinema_test::sample("four_bar.toml"), "--method", "relative-velocity"});
  CHECK(loops.exit_status == 2);
  CHECK(loops.err.find("four_bar.toml: --method relative-velocity works dyad by dyad") != std::string::npos);
  CHECK(loops.out.empty());
  // Session 30's review: a spatial chain was called "vector loops", and a driven chain
  // (seed 000's arm) printed its own derivation with exit 0, the method ignored.
  for (const char* chain : {"rssr_spatial_four_bar.toml", "robot_arm_seed000.toml"}) {
    for (const char* command : {"derive", "latex"}) {
      CAPTURE(chain);
      CAPTURE(command);
      const auto refused = kinema_test::run_kinema({command, kinema_test::sample(chain), "--method", "joint-coordinates"});
      CHECK(refused.exit_status == 2);
      CHECK(refused.out.empty());
      CHECK(refused.err.find("works dyad by dyad") != std::string::npos);
      CHECK(refused.err.find("(this file is a spatial chain of frames)") != std::string::npos);
    }
  }
  const auto unknown = kinema_test::run_kinema({"derive", kinema_test::sample("problem_4_4_joints.toml"), "--method", "graphs"});
  CHECK(unknown.exit_status == 2);
  CHECK(unknown.err.find("--method") != std::string::npos);
}
