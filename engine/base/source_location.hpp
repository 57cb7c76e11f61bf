// Where something was written, carried from the file through every stage so that a
// message names file:line ("four_bar.toml:12").
#pragma once

#include <string>

namespace kinema {

/// Where something was written, for messages ("four_bar.toml:12").
struct SourceLocation {
  std::string file;
  int line = 0;
  std::string str() const { return line > 0 ? file + ":" + std::to_string(line) : file; }
};

}  // namespace kinema
