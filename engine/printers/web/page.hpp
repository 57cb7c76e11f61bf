// kinema page: one self-contained HTML file that animates the mechanism over the solved
// rows (engine/printers/web/page.js and page.css, embedded at configure time). A view
// over results computed before it: the rows are job.values, the drawing's geometry is
// given with the polygons and instant centres of every row (job.analysis, ViewNeeds::motion);
// nothing is solved here.
#pragma once

#include <ostream>

#include "engine/printers/printer.hpp"

namespace kinema {

/// Writes the page of job.values (rows along a circuit when job.circuit) with job.analysis's
/// motion (analysed with ViewNeeds::motion for the same table). Every string from the file
/// reaches the page as JSON data that the page's script shows as text.
void write_page(std::ostream& out, const PrintJob& job);

/// The standard base64 of bytes given as hex digits (a SHA-256 digest for a
/// Content-Security-Policy hash source).
std::string base64_of_hex(const std::string& hex);

}  // namespace kinema
