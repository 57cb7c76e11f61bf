// engine/base/toml_ascii: what toml++ is given. Characters past ASCII in strings and
// comments read as written (through \u escapes); outside them, and bytes that
// are not UTF-8, are refused with file:line; lines stay where they were.
#include <doctest/doctest.h>

#include <string>

#include "engine/base/errors.hpp"
#include "readers/mechanism_file.hpp"
#include "engine/base/toml_ascii.hpp"
#include "tests/test_support.hpp"

using kinema::ascii_toml;
using kinema_test::replaced;

namespace {

std::string error_of(const std::string& text) {
  try {
    ascii_toml(text, "u.toml");
  } catch (const kinema::InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST_CASE("engine/base/toml_ascii: ASCII text is given to the parser as it is") {
  const std::string& text = kinema_test::four_bar_text();
  CHECK(ascii_toml(text, "u.toml") == text);
}

TEST_CASE("engine/base/toml_ascii: strings of every kind and comments keep their characters") {
  // θ (U+03B8) is in the range where toml++ 3.3 reaches __builtin_unreachable; 🙂 needs \U.
  const std::string text = replaced("title = \"four-bar\"",
                                    "# a comment with θ ≠ 0\n"
                                    "title = \"θ ≠ 0, \\\"quoted\\\" 🙂\"\n"
                                    "description = '''\nC:\\path with θ and \"quotes\" '' '''");
  const kinema::Mechanism mechanism = kinema::read_mechanism_text(text, "u.toml");
  CHECK(mechanism.title == "θ ≠ 0, \"quoted\" 🙂");
  CHECK(mechanism.description == "C:\\path with θ and \"quotes\" '' ");
  const kinema::Mechanism literal =
      kinema::read_mechanism_text(replaced("title = \"four-bar\"", "title = 'θ\\x \"y\"'"), "u.toml");
  CHECK(literal.title == "θ\\x \"y\"");
  // Lines are kept: the unknown after a multi-line string with θ is still on its line.
  const std::string shifted = replaced("title = \"four-bar\"", "title = \"\"\"θ\n\n\"\"\"");
  CHECK(kinema::read_mechanism_text(shifted, "u.toml").unknowns[0].where.line == 14);  // 12 + the two added lines
}

TEST_CASE("engine/base/toml_ascii: non-ASCII outside strings, bad UTF-8 and surrogates are refused with the line") {
  CHECK(error_of("a = 1\nθ = 2\n").find("u.toml:2: syntax error") != std::string::npos);
  CHECK(error_of("a = 1\nθ = 2\n").find("U+03B8 is outside a string") != std::string::npos);
  CHECK(error_of("\xc9\x83").find("U+0243") != std::string::npos);  // the fuzzer's finding, outside a string
  CHECK(error_of("t = \"\xc3\x28\"").find("u.toml:1: syntax error in the mechanism file: the bytes are not UTF-8") == 0);
  CHECK(error_of("t = \"\xed\xa0\x80\"").find("not UTF-8") != std::string::npos);  // a surrogate
  CHECK(error_of("t = \"\xc0\xaf\"").find("not UTF-8") != std::string::npos);      // overlong '/'
  CHECK(error_of("t = \"\xf4\x90\x80\x80\"").find("not UTF-8") != std::string::npos);  // past U+10FFFF
  CHECK(error_of("t = \"\xe2\x82\"").find("not UTF-8") != std::string::npos);      // cut short
}

// Audit 2026-11-24: a file saved with a byte-order mark was refused as "U+FEFF outside a
// string", which does not say what to do. A leading BOM is skipped; elsewhere it is a
// character outside a string, named.
TEST_CASE("engine/base/toml_ascii: a leading byte-order mark is skipped, lines as they were") {
  const std::string& text = kinema_test::four_bar_text();
  CHECK(ascii_toml("\xEF\xBB\xBF" + text, "u.toml") == text);
  CHECK(kinema::read_mechanism_text("\xEF\xBB\xBF" + text, "u.toml").unknowns[0].where.line == 12);
  CHECK(error_of("a = 1\n\xEF\xBB\xBF" "b = 2\n").find("u.toml:2: syntax error in the mechanism file: the character U+FEFF") == 0);
}
