// The one place numbers become text: every printer and message formats
// through these, so a value prints the same everywhere.
#pragma once

#include <cstddef>
#include <string>

namespace kinema {

/// `significant` significant digits, %g style ("0.129904", "1e-05"); never "-0".
std::string format_significant(double value, int significant = 6);

/// The same characters written at `out` (at least kMaxNumberChars free); returns
/// the end. What long result runs use: no allocation per number.
char* put_significant(char* out, double value, int significant);

/// `count` values as put_significant writes them, `separator` between them, NaN as
/// nothing (an empty CSV cell); at `out`, (kMaxNumberChars + 1) * count bytes free.
/// The same characters, faster than one put_significant call a value.
char* put_significant_list(char* out, const double* values, std::size_t count, int significant, char separator);

namespace detail {
/// put_significant_list without the vector instructions it uses where the processor has
/// them (AVX-512): what other processors run; for tests that compare the two.
char* put_significant_list_portable(char* out, const double* values, std::size_t count, int significant,
                                    char separator);
/// Whether put_significant_list uses vector instructions on this processor.
bool vector_number_path();
}  // namespace detail

/// The shortest text that reads back as the same double ("0.1", "6.283185307179586",
/// "1e-05"); never "-0". Returns the end.
char* put_shortest(char* out, double value);

/// Room put_significant and put_shortest may need.
constexpr std::size_t kMaxNumberChars = 32;

/// value rounded to `significant` significant digits (what format_significant prints, as a double).
double round_significant(double value, int significant);

/// Enough digits to read back the same double (17 significant).
std::string format_round_trip(double value);

/// Fixed point with `decimals` decimals ("0.129904"), for drawing coordinates.
std::string format_fixed(double value, int decimals = 6);

}  // namespace kinema
