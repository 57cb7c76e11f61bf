// Text from a user (a mechanism file's title, description and strings, a path) as kinema
// writes it out. A character that controls how text is shown rather than being shown —
// a control character (ESC starts terminal escapes), or a bidirectional control that
// reorders what follows it (g++ -Werror=bidi-chars refuses it in a comment) — is refused
// in a mechanism file (readers/mechanism_file.cpp) and never copied into an output.
#pragma once

#include <string>

namespace kinema {

/// The UTF-8 character starting at text[i], i left on its last byte; U+FFFD for bytes
/// that are not UTF-8 (a library caller's text need not be).
unsigned long next_code_point(const std::string& text, std::size_t& i);

/// C0 and C1 control characters and DEL (line breaks and tabs among them), and the line
/// and paragraph separators U+2028 and U+2029, which break a line as a line feed does.
bool is_control_character(unsigned long c);

/// The bidirectional controls: U+061C, U+200E, U+200F, U+202A-U+202E, U+2066-U+2069.
bool is_bidi_control(unsigned long c);

/// "U+202E".
std::string code_point_name(unsigned long c);

/// text for one line of a comment or a message: control characters (line breaks, tabs,
/// ESC) become spaces, bidirectional controls and bytes that are not UTF-8 their code
/// point in brackets ([U+202E]); everything else as it is.
std::string one_line(const std::string& text);

/// text for a message on the terminal, such as one that repeats a path: line breaks kept,
/// every other control character (ESC would start a terminal escape), bidirectional control
/// (U+202E would reverse what follows) and byte that is not UTF-8 shown as its code point in
/// brackets ([U+001B]), so that the message shows the name as it is without acting on it.
std::string terminal_text(const std::string& text);

}  // namespace kinema
