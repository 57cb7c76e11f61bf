#include "engine/printers/printer.hpp"

#include <stdexcept>

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

ViewNeeds Printer::needs(const PrintJob&) const { return {}; }

ViewNeeds derivation_needs(const PrintJob& job, bool by_dyads) {
  ViewNeeds needs;
  needs.dyad_derivation = by_dyads && job.method != DerivationMethod::loops;
  needs.chain_at_instant = true;  // worked out only for a driven chain (analyse_for_views)
  needs.method = job.method;
  needs.basis = job.basis;
  return needs;
}

const Analysis& analysis_of(const PrintJob& job) {
  if (!job.analysis) throw std::logic_error("a printer was given no analysis: build it with analyse_for_views");
  return *job.analysis;
}

std::vector<std::string> printer_names(PrintKind kind) {
  std::vector<std::string> names;
  for (const Printer* printer : all_printers())
    if (printer->kind() == kind) names.push_back(printer->name());
  return names;
}

}  // namespace kinema
