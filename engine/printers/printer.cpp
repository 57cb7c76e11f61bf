#include <kinema/engine/printers/printer.hpp>

namespace kinema {

// Each printer file defines its printer; this list is the registry.
const Printer& derivation_text_printer();
const Printer& derivation_latex_printer();
const Printer& results_table_printer();
const Printer& csv_printer();
const Printer& json_printer();
const Printer& npy_printer();
const Printer& worked_solution_printer();
const Printer& cpp_header_printer();

namespace {

const std::vector<const Printer*>& all_printers() {
  static const std::vector<const Printer*> printers = {
      &derivation_text_printer(), &derivation_latex_printer(), &results_table_printer(), &csv_printer(),
      &json_printer(),            &npy_printer(),              &worked_solution_printer(), &cpp_header_printer()};
  return printers;
}

}  // namespace

const Printer* find_printer(PrintKind kind, std::string_view name) {
  for (const Printer* printer : all_printers())
    if (printer->kind() == kind && name == printer->name()) return printer;
  return nullptr;
}

std::vector<std::string> printer_names(PrintKind kind) {
  std::vector<std::string> names;
  for (const Printer* printer : all_printers())
    if (printer->kind() == kind) names.push_back(printer->name());
  return names;
}

}  // namespace kinema
