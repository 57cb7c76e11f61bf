// The one place numbers become text: every printer and message formats
// through these, so a value prints the same everywhere.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <string>

namespace kinema {

/// `significant` significant digits, %g style ("0.129904", "1e-05"); never "-0".
std::string format_significant(double value, int significant = 6);

/// Zero at the problem's scale: a value below this fraction of the scale it is shown at
/// is the solvers' round-off (their relative accuracy, about 1e-15, with room) and is
/// shown as 0, not as "1.00804e-16" beside 1.64625. Every view of numbers for people
/// (the table, the LaTeX, the page, the derivation) shows values through zero_at_scale;
/// the data formats (CSV, JSON, npy) write the values as solved.
inline constexpr double kRoundOffFraction = 1e-12;

/// `value`, or 0 where |value| < kRoundOffFraction * scale. `scale`: what the view knows
/// of the value's size, the largest of the magnitudes shown with it (its column, its
/// vector's components; largest_magnitude) and the problem's own size for its kind
/// (engine/analysis/problem_scale); 0 zeroes nothing. NaN and infinities stay.
double zero_at_scale(double value, double scale);

/// format_significant of zero_at_scale(value, scale).
std::string format_at_scale(double value, double scale, int significant = 6);

/// The largest finite magnitude among values (0 where there is none): the scale of numbers
/// shown together.
double largest_magnitude(const double* values, std::size_t count);
double largest_magnitude(std::initializer_list<double> values);

/// The same characters written at `out` (at least kMaxNumberChars free); returns
/// the end. What long result runs use: no allocation per number.
char* put_significant(char* out, double value, int significant);

/// `count` values as put_significant writes them, `separator` between them, NaN as
/// nothing (an empty CSV cell); at `out`, (kMaxNumberChars + 1) * count bytes free.
/// The same characters, faster than one put_significant call a value.
char* put_significant_list(char* out, const double* values, std::size_t count, int significant, char separator);

/// Whether put_significant_list and SignificantChunk use vector instructions on this
/// processor (AVX-512).
bool vector_number_path();

/// Room put_significant and put_shortest may need.
constexpr std::size_t kMaxNumberChars = 32;

/// Up to `capacity` numbers written as put_significant writes them (NaN as nothing), for
/// 1 to 13 significant digits: the arithmetic of all of them first, eight at a time with
/// vector instructions where the processor has them, then each text (by one byte shuffle
/// where it has AVX-512 VBMI, but for scientific notation). What runs of
/// numbers that are not one list (rows with other text between) are written with.
class SignificantChunk {
 public:
  static constexpr std::size_t capacity = 64;
  /// Whether `significant` digits are within what a chunk writes (1 to 13: the rounded
  /// mantissa stays below 10^13, exact in a double).
  static constexpr bool handles(int significant) { return significant >= 1 && significant <= 13; }
  /// values[0, count) (count <= capacity; they stay readable until the last put).
  /// `vector` false: without vector instructions (what other processors run; for tests).
  void convert(const double* values, std::size_t count, int significant, bool vector = vector_number_path());
  /// Values [first, last) of the chunk, `separator` between them, at out
  /// ((kMaxNumberChars + 1) * (last - first) bytes free); returns the end.
  char* put(char* out, std::size_t first, std::size_t last, char separator) const;

  struct Digits {
    alignas(64) char texts[capacity + 1][16];  // 16 digits a value; one more row: room to read past the last
    int exponents[capacity];
    unsigned char kinds[capacity];
  };

 private:
  Digits digits_;
  const double* values_ = nullptr;
  int significant_ = 0;
  bool shuffled_texts_ = false;  // put writes plain notation by byte shuffles (AVX-512 VBMI)
};

/// The shortest text that reads back as the same double ("0.1", "6.283185307179586",
/// "1e-05"); never "-0". Returns the end.
char* put_shortest(char* out, double value);

/// value rounded to `significant` significant digits (what format_significant prints, as a double).
double round_significant(double value, int significant);

/// Enough digits to read back the same double (17 significant).
std::string format_round_trip(double value);

/// Fixed point with `decimals` decimals ("0.129904"), for drawing coordinates; a value
/// that rounds to zero is "0.000", never "-0.000".
std::string format_fixed(double value, int decimals = 6);

}  // namespace kinema
