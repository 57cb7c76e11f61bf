// One analysis, computed once (issue 34): what a view shows beyond the table is worked out
// by analyse_for_views before any printer runs, and a printer given it only formats. The
// engine's counts of solved values and of each kind of costly work are read around each
// step: printing adds nothing to them, the analysis does what the view shows.
#include <doctest/doctest.h>

#include <array>
#include <cstdint>
#include <sstream>
#include <string>

#include "engine/base/work_count.hpp"
#include "engine/model.hpp"
#include "engine/numeric/sweep.hpp"
#include "engine/printers/printer.hpp"
#include "engine/run/view.hpp"
#include "tests/test_support.hpp"

using kinema::PrintKind;
using kinema::Work;

namespace {

// Every counter the engine keeps of its work, in one snapshot.
struct WorkDone {
  std::uint64_t values_solved = kinema::values_solved_in_process();
  std::array<std::uint64_t, static_cast<std::size_t>(Work::kCount)> work = counts();
  static std::array<std::uint64_t, static_cast<std::size_t>(Work::kCount)> counts() {
    std::array<std::uint64_t, static_cast<std::size_t>(Work::kCount)> done{};
    for (std::size_t w = 0; w < done.size(); ++w) done[w] = kinema::work_done_in_process(static_cast<Work>(w));
    return done;
  }
  std::uint64_t operator[](Work w) const { return work[static_cast<std::size_t>(w)]; }
  bool operator==(const WorkDone& other) const { return values_solved == other.values_solved && work == other.work; }
};

// Analyses the job for the printer, then prints it: the work each step did.
struct Printed {
  WorkDone before, analysed, printed;
  std::string text;
};

Printed analyse_then_print(PrintKind kind, const char* name, kinema::PrintJob job) {
  const kinema::Printer* printer = kinema::find_printer(kind, name);
  REQUIRE(printer != nullptr);
  Printed result;
  const kinema::Analysis analysis = kinema::analyse_for_printer(*printer, job);
  result.analysed = WorkDone{};
  job.analysis = &analysis;
  std::ostringstream out;
  printer->print(out, job);
  result.printed = WorkDone{};
  result.text = out.str();
  return result;
}

}  // namespace

TEST_CASE("a printer given the analysis solves, derives and analyses nothing: the analysis did it, once") {
  SUBCASE("the table's and JSON's heads: a four-bar's figures over the turn, solved in the analysis") {
    const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
    const kinema::MotionTable values = kinema::solve_motion(model, model.system.input.values);
    for (const char* format : {"table", "json"}) {
      CAPTURE(format);
      const WorkDone before;
      const Printed p = analyse_then_print(PrintKind::results, format, kinema::PrintJob{model, &values});
      CHECK(p.analysed[Work::design_figures] - before[Work::design_figures] == 2);  // figures and strokes
      CHECK(p.analysed.values_solved > before.values_solved);                         // the turn, solved
      CHECK(p.printed == p.analysed);
      CHECK(p.text.find("rashof") != std::string::npos);  // Grashof (table), "grashof" (JSON)
    }
  }
  SUBCASE("a derivation dyad by dyad, and a worked solution with its drawings, polygons and centres") {
    const kinema::Model model = kinema::load_model(kinema_test::sample("example_4_2_joints.toml"), kinema::DerivationScope::full);
    const kinema::MotionTable values = kinema::solve_motion(model, model.system.input.values);
    kinema::PrintJob job{model, &values};
    job.method = kinema::DerivationMethod::relative_velocity;
    for (const PrintKind kind : {PrintKind::derivation, PrintKind::document}) {
      const WorkDone before;
      const Printed p = analyse_then_print(kind, "latex", job);
      CHECK(p.analysed[Work::dyad_derivation] - before[Work::dyad_derivation] == 1);
      if (kind == PrintKind::document) CHECK(p.analysed[Work::drawing] > before[Work::drawing]);
      CHECK(p.printed == p.analysed);
    }
    const WorkDone before;
    const Printed text = analyse_then_print(PrintKind::derivation, "text", job);
    CHECK(text.analysed[Work::dyad_derivation] - before[Work::dyad_derivation] == 1);
    CHECK(text.printed == text.analysed);
  }
  SUBCASE("a spatial chain worked out at the instant, in text and in a document") {
    const kinema::Model model = kinema::load_model(kinema_test::sample("robot_arm_seed000.toml"), kinema::DerivationScope::full);
    const kinema::MotionTable values = kinema::solve_motion(model, model.system.input.values);
    for (const PrintKind kind : {PrintKind::derivation, PrintKind::document}) {
      const WorkDone before;
      const Printed p = analyse_then_print(kind, kind == PrintKind::derivation ? "text" : "latex", kinema::PrintJob{model, &values});
      CHECK(p.analysed[Work::chain_at_instant] - before[Work::chain_at_instant] == 1);
      CHECK(p.printed == p.analysed);
    }
  }
}

TEST_CASE("a printer that needs an analysis and is given none says so, rather than working it out") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::MotionTable values = kinema::solve_motion(model, model.system.input.values);
  std::ostringstream out;
  CHECK_THROWS_AS(kinema::find_printer(PrintKind::results, "table")->print(out, kinema::PrintJob{model, &values}),
                  std::logic_error);
  // A format that shows nothing beyond the table needs none.
  CHECK_NOTHROW(kinema::find_printer(PrintKind::results, "csv")->print(out, kinema::PrintJob{model, &values}));
}
