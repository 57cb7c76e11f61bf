// Putting finished text where the user asked: a file given with -o, or stdout.
// Every write is checked; a file is replaced only by a complete new one.
#pragma once

#include <string>

#include <kinema/engine/errors.hpp>

namespace kinema_cli {

/// The output cannot be written (missing directory, no permission, disk full,
/// short write). The message names the path and the system's reason.
class OutputError : public kinema::Error {
 public:
  using kinema::Error::Error;
};

/// Writes text to path, or to stdout when path is "" or "-".
void write_output(const std::string& text, const std::string& path);

/// Writes text to a temporary file created in path's directory, syncs and
/// closes it, then renames it over path. On any failure the temporary is
/// removed, a previous file at path is left as it was, and OutputError is thrown.
void write_file(const std::string& text, const std::string& path);

/// Writes text to stdout and flushes it; OutputError on a failed or short write.
void write_standard_output(const std::string& text);

/// Flushes std::cout and stdout (help, version, anything still buffered);
/// OutputError if that or any earlier write to them failed.
void flush_standard_output();

}  // namespace kinema_cli
