#include "engine/run/view.hpp"

#include "engine/analysis/motion_drawing.hpp"
#include "engine/printers/web/page.hpp"

namespace kinema {

Analysis analyse_for_printer(const Printer& printer, const PrintJob& job) {
  return analyse_for_views(job.model, job.values, printer.needs(job));
}

void print_view(const Printer& printer, std::ostream& out, PrintJob job) {
  const Analysis analysis = analyse_for_printer(printer, job);
  job.analysis = &analysis;
  printer.print(out, job);
}

void print_page(std::ostream& out, const Model& model, const MotionTable& table, bool circuit) {
  const MotionDrawing drawing = motion_drawing(model, table);
  PrintJob job{model, &table};
  job.circuit = circuit;
  write_page(out, job, drawing);
}

}  // namespace kinema
