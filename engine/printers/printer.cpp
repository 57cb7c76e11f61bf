#include "engine/printers/printer.hpp"

#include <algorithm>
#include <stdexcept>

#include "engine/analysis/output_scale.hpp"

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

std::vector<ResultColumn> printed_columns(const PrintJob& job) {
  const ConstraintSystem& system = job.model.system;
  std::vector<ResultColumn> columns = result_columns(system, OutputScale(system), job.circuit);
  if (job.sensitivities)
    for (const SensitivityColumn& column : *job.sensitivities) columns.push_back(column.named);
  return columns;
}

std::size_t printed_column_count(const PrintJob& job) {
  return result_column_count(job.model.system, job.circuit) +
         (job.sensitivities ? job.sensitivities->size() : 0);
}

void printed_rows(const PrintJob& job, const MotionTable& table, std::size_t first, std::size_t last, double* values) {
  const ConstraintSystem& system = job.model.system;
  if (!job.sensitivities) {
    result_rows(system, OutputScale(system), table, first, last, values);
    return;
  }
  const std::size_t results = result_column_count(system, table.is_circuit()),
                    derived = job.sensitivities->size(), rows = last - first;
  if (table.derived_count() != derived) throw std::logic_error("printed_rows: the sensitivities were not filled in");
  std::vector<double> own(rows * results);
  result_rows(system, OutputScale(system), table, first, last, own.data());
  for (std::size_t r = 0; r < rows; ++r) {
    values = std::copy_n(own.data() + r * results, results, values);
    for (std::size_t k = 0; k < derived; ++k) *values++ = table.derived_column(k)[first + r];
  }
}

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
