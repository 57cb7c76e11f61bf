// libFuzzer target: the mechanism-file reader (TOML parse and every check in
// readers/). A file may be refused (kinema::InputError); any other
// exception would reach the user as an "internal error", so it stops the fuzzer.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string>

#include "engine/base/errors.hpp"
#include "readers/mechanism_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > kinema::kMaxMechanismFileBytes) return -1;  // read_mechanism_file refuses these unread
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)kinema::read_mechanism_text(text, "fuzz.toml");
  } catch (const kinema::Error&) {
    // Refused with a message: what should happen to bad input.
  } catch (const std::exception&) {
    std::abort();
  }
  return 0;
}
