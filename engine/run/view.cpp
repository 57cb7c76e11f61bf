#include "engine/run/view.hpp"

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
  PrintJob job{model, &table};
  job.circuit = circuit;
  // The page shows the derivation as `kinema derive --format latex` prints it (in MathML).
  ViewNeeds needs = find_printer(PrintKind::derivation, "latex")->needs(job);
  needs.motion = true;
  needs.slider_ranges = !circuit;  // a circuit's page has no sliders
  const Analysis analysis = analyse_for_views(model, &table, needs);
  job.analysis = &analysis;
  write_page(out, job);
}

}  // namespace kinema
