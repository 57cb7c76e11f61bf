#include "engine/run/view.hpp"

namespace kinema {

Analysis analyse_for_printer(const Printer& printer, const PrintJob& job) {
  return analyse_for_views(job.model, job.values, printer.needs(job));
}

void print_view(const Printer& printer, std::ostream& out, PrintJob job) {
  const Analysis analysis = analyse_for_printer(printer, job);
  job.analysis = &analysis;
  printer.print(out, job);
}

}  // namespace kinema
