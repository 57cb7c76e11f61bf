// Putting finished text where the user asked: a file given with -o, or stdout.
// Every write is checked; a file is replaced only by a complete new one.
#pragma once

#include <string>
#include <string_view>

#include "engine/base/errors.hpp"

namespace kinema_cli {

/// The output cannot be written (missing directory, no permission, disk full,
/// short write). The message names the path and the system's reason.
class OutputError : public kinema::Error {
 public:
  using kinema::Error::Error;
};

/// Output written piece by piece that appears only when complete. A file given with -o
/// is written to a temporary created exclusively in its directory and renamed over it
/// by commit(); an Output destroyed (or failing) before commit removes the temporary
/// and leaves a previous file at path as it was; a file this user may not write is
/// refused, as the shell's > refuses it (the rename would replace it all the same). A
/// symbolic link stays a link, its target (made if missing) gets the text. A character device, FIFO or socket,
/// and stdout ("" or "-"), take the pieces as they come. Failures throw OutputError
/// naming the path and the system's reason.
class Output {
 public:
  explicit Output(const std::string& path);
  ~Output();
  Output(const Output&) = delete;
  Output& operator=(const Output&) = delete;
  void write(std::string_view text);
  void commit();

 private:
  [[noreturn]] void fail(int error_number);
  std::string shown_, path_, temporary_;
  int fd_ = -1;
  bool owns_fd_ = false;
};

/// Refuses (OutputError) an output that Output would not write: a file or a directory
/// this user may not write (as the shell's > would), a symbolic link loop. For a check
/// before any work; Output checks again when it opens.
void check_output(const std::string& path);

/// Writes text to path, or to stdout when path is "" or "-" (an Output written at once).
void write_output(const std::string& text, const std::string& path);

/// Flushes std::cout and stdout (help, version, anything still buffered);
/// OutputError if that or any earlier write to them failed.
void flush_standard_output();

}  // namespace kinema_cli
