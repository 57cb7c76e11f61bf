// A view printed the one way every caller prints it (the command, the library's tests):
// what the printer needs analysed once (analyse_for_views), then the printer formatting
// the results and that analysis.
#pragma once

#include <ostream>

#include "engine/analysis/analysis.hpp"
#include "engine/printers/printer.hpp"

namespace kinema {

/// What `printer` shows of `job` beyond the results, computed (its Printer::needs).
Analysis analyse_for_printer(const Printer& printer, const PrintJob& job);

/// Prints job with `printer`, its analysis computed first (job.analysis is replaced).
void print_view(const Printer& printer, std::ostream& out, PrintJob job);

/// The page (engine/printers/web/page) over `table`, solved already (rows along a circuit
/// when `circuit`), its motion analysed here once (the drawing's geometry, polygons and
/// instant centres of every row): `kinema page` and the Python
/// module's Model.page() print it the one way.
void print_page(std::ostream& out, const Model& model, const MotionTable& table, bool circuit);

}  // namespace kinema
