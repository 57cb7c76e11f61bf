// engine/printers/printer: printers found by kind and name, as --format names them.
#include <doctest/doctest.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/run/view.hpp"
#include "engine/printers/printer.hpp"
#include "tests/test_support.hpp"

using kinema::find_printer;
using kinema::PrintKind;
using kinema::printer_names;
using Names = std::vector<std::string>;

TEST_CASE("engine/printers/printer: find_printer by kind and name") {
  const PrintKind kinds[] = {PrintKind::derivation, PrintKind::results, PrintKind::document, PrintKind::code};
  std::set<const kinema::Printer*> all;
  for (PrintKind kind : kinds) {
    for (const std::string& name : printer_names(kind)) {
      CAPTURE(name);
      const kinema::Printer* printer = find_printer(kind, name);
      REQUIRE(printer != nullptr);
      CHECK(printer->kind() == kind);
      CHECK(printer->name() == name);
      CHECK(find_printer(kind, name) == printer);  // one printer per name, the same each time
      all.insert(printer);
    }
  }
  CHECK(all.size() == 8);
  // "latex" is two printers: the derivation block and the worked solution.
  CHECK(find_printer(PrintKind::derivation, "latex") != find_printer(PrintKind::document, "latex"));
  CHECK(find_printer(PrintKind::document, "latex")->kind() == PrintKind::document);
}

TEST_CASE("engine/printers/printer: unknown names and wrong kinds find nothing") {
  CHECK(find_printer(PrintKind::results, "xml") == nullptr);
  CHECK(find_printer(PrintKind::results, "") == nullptr);
  CHECK(find_printer(PrintKind::results, "CSV") == nullptr);    // names are exact
  CHECK(find_printer(PrintKind::results, "csv ") == nullptr);
  CHECK(find_printer(PrintKind::derivation, "csv") == nullptr);  // csv prints results, not derivations
  CHECK(find_printer(PrintKind::results, "text") == nullptr);
  CHECK(find_printer(PrintKind::code, "latex") == nullptr);
  CHECK(find_printer(PrintKind::document, "cpp") == nullptr);
}

TEST_CASE("engine/printers/printer: printer_names in a stable order") {
  CHECK(printer_names(PrintKind::derivation) == Names{"text", "latex"});
  CHECK(printer_names(PrintKind::results) == Names{"table", "csv", "json", "npy"});
  CHECK(printer_names(PrintKind::document) == Names{"latex"});
  CHECK(printer_names(PrintKind::code) == Names{"cpp"});
  CHECK(printer_names(PrintKind::results) == printer_names(PrintKind::results));
}

TEST_CASE("engine/printers/printer: each printer prints something of its own from one model") {
  const kinema::Model model = kinema::load_model(kinema_test::sample("four_bar.toml"));
  const kinema::MotionTable values = kinema::solve_motion(model, {0.7});
  kinema::PrintJob job{model, &values};
  job.code_namespace = "unit_four_bar";
  std::set<std::string> outputs;
  for (PrintKind kind : {PrintKind::derivation, PrintKind::results, PrintKind::document, PrintKind::code}) {
    for (const std::string& name : printer_names(kind)) {
      CAPTURE(name);
      std::ostringstream out;
      kinema::print_view(*find_printer(kind, name), out, job);
      CHECK(out.str().size() > 100);
      outputs.insert(out.str());
    }
  }
  CHECK(outputs.size() == 8);  // no two printers print the same
  std::ostringstream code;
  kinema::print_view(*find_printer(PrintKind::code, "cpp"), code, job);
  CHECK(code.str().find("namespace unit_four_bar") != std::string::npos);
}
