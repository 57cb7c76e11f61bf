#include "engine/printers/printer.hpp"

namespace kinema {

// Each printer file defines its printer; this list is the registry.
const Printer& derivation_text_printer();
const Printer& derivation_latex_printer();
const ResultsPrinter& results_table_printer();
const ResultsPrinter& csv_printer();
const ResultsPrinter& json_printer();
const ResultsPrinter& npy_printer();
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

const ResultsPrinter* find_results_printer(std::string_view name) {
  return dynamic_cast<const ResultsPrinter*>(find_printer(PrintKind::results, name));
}

void ResultsPrinter::print(std::ostream& out, const PrintJob& job) const {
  const std::size_t rows = job.values ? job.values->size() : 0;
  std::string text;
  head(text, job, rows);
  if (job.values) this->rows(text, job, *job.values, 0, rows, 0);
  tail(text, job, rows);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
}

std::vector<std::string> printer_names(PrintKind kind) {
  std::vector<std::string> names;
  for (const Printer* printer : all_printers())
    if (printer->kind() == kind) names.push_back(printer->name());
  return names;
}

}  // namespace kinema
