// The mechanism file as toml++ is given it: ASCII only. toml++ 3.3 reaches
// __builtin_unreachable() (undefined behaviour; found by tests/fuzz) when it tests a
// character between U+00A1 and U+0499 (Greek letters among them) for whitespace. So
// characters past ASCII, which a mechanism file has only in strings (a title with θ)
// and comments, are rewritten before parsing: in a string as a \uXXXX escape (a
// literal string becomes the equivalent basic string), in a comment as '?'. Lines stay
// where they are, so messages keep their file:line.
#pragma once

#include <string>

namespace kinema {

/// `text` with every non-ASCII character rewritten as above; ASCII text is returned as it is.
/// Throws InputError("file:line: ...") for bytes that are not UTF-8 and for non-ASCII
/// characters outside strings and comments.
std::string ascii_toml(const std::string& text, const std::string& file);

}  // namespace kinema
