// kinema page: one self-contained HTML file that animates the mechanism over the solved
// rows (engine/printers/web/page.js and page.css, embedded at configure time). A view
// over results computed before it: the rows are job.values, the drawing's geometry is
// given (engine/analysis/motion_drawing); nothing is solved here.
#pragma once

#include <ostream>

#include "engine/printers/printer.hpp"
#include "engine/analysis/motion_drawing.hpp"

namespace kinema {

/// Writes the page of job.values (rows along a circuit when job.circuit) drawn with `drawing`
/// (motion_drawing of the same table). Every string from the file reaches the page as
/// JSON data that the page's script shows as text.
void write_page(std::ostream& out, const PrintJob& job, const MotionDrawing& drawing);

/// The standard base64 of bytes given as hex digits (a SHA-256 digest for a
/// Content-Security-Policy hash source).
std::string base64_of_hex(const std::string& hex);

}  // namespace kinema
