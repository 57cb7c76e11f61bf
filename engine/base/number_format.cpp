#include "engine/base/number_format.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace kinema {

namespace {

// 10^k for |k| <= kPowers, each correctly rounded (strtod rounds correctly).
constexpr int kPowers = 300;
const std::array<double, 2 * kPowers + 1>& powers_of_ten() {
  static const auto table = [] {
    std::array<double, 2 * kPowers + 1> powers{};
    for (int k = -kPowers; k <= kPowers; ++k) powers[k + kPowers] = std::strtod(("1e" + std::to_string(k)).c_str(), nullptr);
    return powers;
  }();
  return table;
}

constexpr char kDigitPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Exactly 8 decimal digits of value < 10^8, as four independent pairs (no chain of
// dependent divisions: this is the inner loop of a CSV of millions of numbers).
void put_8_digits(char* out, std::uint32_t value) {
  const std::uint32_t high = value / 10000, low = value % 10000;
  std::memcpy(out, kDigitPairs + 2 * (high / 100), 2);
  std::memcpy(out + 2, kDigitPairs + 2 * (high % 100), 2);
  std::memcpy(out + 4, kDigitPairs + 2 * (low / 100), 2);
  std::memcpy(out + 6, kDigitPairs + 2 * (low % 100), 2);
}

// The 16 decimal digits of value < 10^16, leading zeros included.
void put_16_digits(char* out, std::uint64_t value) {
  put_8_digits(out, static_cast<std::uint32_t>(value / 100000000));
  put_8_digits(out + 8, static_cast<std::uint32_t>(value % 100000000));
}

// Copies of 16 bytes whatever the length needed (the buffers have the room): a
// variable-length memcpy is a library call, and this runs three times a number.
void copy_16(char* to, const char* from) { std::memcpy(to, from, 16); }

// A magnitude rounded to `digits` significant digits: mantissa * 10^(exponent - digits + 1),
// 10^(digits-1) <= mantissa < 10^digits.
struct Decimal {
  std::uint64_t mantissa;
  int exponent;
};

// The Decimal of a finite non-zero magnitude with `digits` <= 13 significant digits, or
// false when the scaled value is too close to a rounding tie to decide in double
// arithmetic (the caller then asks std::to_chars, which decides exactly). The scaling
// magnitude * 10^k errs by at most about 2.3e-16 relative, i.e. 10^digits * 2.3e-16 in
// the last digit; the window below is over four times that.
bool to_decimal(double magnitude, int digits, Decimal& decimal) {
  const auto& powers = powers_of_ten();
  if (!(magnitude >= 1e-280 && magnitude <= 1e280)) return false;
  // floor(log10(magnitude)) to within one (corrected below) from the binary exponent:
  // floor(e2 log10 2) = (e2 * 78913) >> 18 for the exponents of normal doubles.
  std::uint64_t bits;
  std::memcpy(&bits, &magnitude, sizeof bits);
  const int binary_exponent = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  int exponent = (binary_exponent * 78913) >> 18;
  const double low = powers[kPowers + digits - 1], high = powers[kPowers + digits];
  double scaled = magnitude * powers[kPowers + digits - 1 - exponent];
  if (scaled < low) scaled = magnitude * powers[kPowers + digits - 1 - --exponent];
  else if (scaled >= high) scaled = magnitude * powers[kPowers + digits - 1 - ++exponent];
  auto mantissa = static_cast<std::uint64_t>(scaled);  // floor: scaled > 0
  const double fraction = scaled - static_cast<double>(mantissa);
  if (std::fabs(fraction - 0.5) < high * 1e-15) return false;
  if (fraction > 0.5) ++mantissa;
  if (mantissa >= static_cast<std::uint64_t>(high)) {  // 9.99...95 rounded up to 10.0...
    mantissa /= 10;
    ++exponent;
  }
  decimal = {mantissa, exponent};
  return true;
}

// How many of the `digits` significant digits at the end of text[0..16) are kept: %g
// drops trailing zeros. The last digit that is not '0', found a word at a time.
int kept_digits(const char* all_digits, int digits) {
  std::uint64_t low, high;
  std::memcpy(&low, all_digits, 8);
  std::memcpy(&high, all_digits + 8, 8);
  low ^= 0x3030303030303030ULL;  // '0' bytes become zero bytes
  high ^= 0x3030303030303030ULL;
  // Byte i is all_digits[i] (little-endian): the highest non-zero byte is the last digit kept.
  const int last = high != 0 ? 8 + (63 - __builtin_clzll(high)) / 8 : low != 0 ? (63 - __builtin_clzll(low)) / 8 : 15;
  return std::max(1, last - (16 - digits) + 1);
}

// %g at out (kMaxNumberChars - 1 bytes free) of the number whose 16 digits (leading
// zeros first) are at all_digits, with 16 more bytes readable after them.
char* put_digits(char* out, const char* all_digits, int exponent, int digits) {
  const char* text = all_digits + 16 - digits;
  const int length = kept_digits(all_digits, digits);
  // out has kMaxNumberChars - 1 bytes (a sign may precede): each copy_16 below stays inside.
  if (exponent < -4 || exponent >= digits) {  // scientific: d.ddd e+XX
    out[0] = text[0];
    if (length > 1) {
      out[1] = '.';
      copy_16(out + 2, text + 1);
      out += length + 1;
    } else {
      out += 1;
    }
    *out++ = 'e';
    *out++ = exponent < 0 ? '-' : '+';
    const int e = std::abs(exponent);
    if (e >= 100) *out++ = static_cast<char>('0' + e / 100);
    std::memcpy(out, kDigitPairs + 2 * (e % 100), 2);
    return out + 2;
  }
  if (exponent >= 0) {  // ddd.ddd
    const int whole_digits = exponent + 1;
    copy_16(out, text);
    if (length <= whole_digits) return out + whole_digits;
    out[whole_digits] = '.';
    copy_16(out + whole_digits + 1, text + whole_digits);
    return out + length + 1;
  }
  out[0] = '0';  // 0.000ddd
  out[1] = '.';
  out[2] = out[3] = out[4] = '0';
  out += 1 - exponent;
  copy_16(out, text);
  return out + length;
}


// %g of a finite non-zero magnitude with `digits` <= 13 significant digits, or nullptr
// near a rounding tie (see to_decimal).
char* put_significant_fast(char* out, double magnitude, int digits) {
  Decimal decimal;
  if (!to_decimal(magnitude, digits, decimal)) return nullptr;
  char all_digits[32];
  put_16_digits(all_digits, decimal.mantissa);
  return put_digits(out, all_digits, decimal.exponent, digits);
}

// A list is formatted in chunks, in passes: every value of a chunk to its 16 digits and
// decimal exponent (the arithmetic), then each text. Apart, a pass's work overlaps from
// one value to the next, and the texts read digits stored long before (reading bytes
// just stored in pieces stalls).
enum Kind : unsigned char { kNumber, kZero, kEmpty, kExact };
constexpr std::size_t kChunk = SignificantChunk::capacity;
using ChunkDigits = SignificantChunk::Digits;

unsigned char kind_of(double value) {
  if (value == 0) return kZero;
  if (std::isnan(value)) return kEmpty;
  return kExact;
}

// Entry k of a converted chunk at out (kMaxNumberChars free), as put_significant writes it.
char* put_entry(char* out, const ChunkDigits& chunk, const double* values, std::size_t k, int digits) {
  switch (chunk.kinds[k]) {
    case kNumber:
      *out = '-';  // kept for a negative value only
      return put_digits(out + std::signbit(values[k]), chunk.texts[k], chunk.exponents[k], digits);
    case kZero:
      *out = '0';
      return out + 1;
    case kEmpty:
      return out;
    case kExact:
      break;
  }
  return std::to_chars(out, out + kMaxNumberChars, values[k], std::chars_format::general, digits).ptr;
}

void chunk_digits_portable(const double* values, std::size_t n, int digits, ChunkDigits& chunk) {
  Decimal decimals[kChunk];
  for (std::size_t k = 0; k < n; ++k) {
    const double value = values[k];
    decimals[k] = {0, 0};  // the digits pass converts every entry
    chunk.kinds[k] = std::isfinite(value) && value != 0 && to_decimal(std::fabs(value), digits, decimals[k])
                         ? static_cast<unsigned char>(kNumber)
                         : kind_of(value);
  }
  for (std::size_t k = 0; k < n; ++k) {  // also unused ones: no branch
    put_16_digits(chunk.texts[k], decimals[k].mantissa);
    chunk.exponents[k] = decimals[k].exponent;
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
#define KINEMA_VECTOR_NUMBERS 1
// GCC 12's intrinsics (_mm512_set1_*) trip its own -Wmaybe-uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#define KINEMA_AVX512 __attribute__((target("avx512f,avx512dq,avx512bw,avx512vl")))

// x = high * unit + low in each lane, for whole x < 10^13 and unit 10^4 or 10^8: exact,
// since x * (1 / unit) errs by far less than the 0.5 / unit that keeps the floor off a
// quotient that is a whole number.
KINEMA_AVX512 __m512d split(__m512d x, double unit, __m512d& low) {
  const __m512d high = _mm512_roundscale_pd(_mm512_mul_pd(_mm512_add_pd(x, _mm512_set1_pd(0.5)), _mm512_set1_pd(1 / unit)),
                                            _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
  low = _mm512_fnmadd_pd(high, _mm512_set1_pd(unit), x);
  return high;
}

// Each 16-bit lane < 100 as its two ASCII digits (the tens in the low byte).
KINEMA_AVX512 __m512i pair_text(__m512i pair) {
  const __m512i tens = _mm512_mulhi_epu16(pair, _mm512_set1_epi16(6554));
  const __m512i units = _mm512_sub_epi16(pair, _mm512_mullo_epi16(tens, _mm512_set1_epi16(10)));
  return _mm512_or_si512(_mm512_or_si512(tens, _mm512_slli_epi16(units, 8)), _mm512_set1_epi16(0x3030));
}

// The 16 decimal digits (leading zeros first) of each lane's integer mantissa < 10^13,
// as eight 16-byte texts at out: split in groups of 4 digits in double arithmetic, the 32
// groups in one register of 16-bit lanes, then hundreds and tens of all of them at once
// (a multiply-high each: 5243 / 2^19 and 6554 / 2^16 give g / 100 for g < 10^4 and
// p / 10 for p < 100 exactly): fewer and cheaper operations than 64-bit multiplies in
// 64-bit lanes, which took over half of the digits' time.
KINEMA_AVX512 void sixteen_digits(__m512d mantissa, char (*out)[16]) {
  __m512d last8, group1, group3;
  const __m512d first8 = split(mantissa, 1e8, last8);
  const __m512d group0 = split(first8, 1e4, group1), group2 = split(last8, 1e4, group3);
  const __m512i first = _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvttpd_epi32(group0)), _mm512_cvttpd_epi32(group1), 1);
  const __m512i last = _mm512_inserti64x4(_mm512_castsi256_si512(_mm512_cvttpd_epi32(group2)), _mm512_cvttpd_epi32(group3), 1);
  // Number n's four groups in 16-bit lanes 4n..4n+3 (each the low half of a 32-bit lane).
  const __m512i groups = _mm512_permutex2var_epi16(
      first,
      _mm512_set_epi16(62, 46, 30, 14, 60, 44, 28, 12, 58, 42, 26, 10, 56, 40, 24, 8, 54, 38, 22, 6, 52, 36, 20, 4, 50, 34,
                       18, 2, 48, 32, 16, 0),
      last);
  const __m512i hundreds = _mm512_srli_epi16(_mm512_mulhi_epu16(groups, _mm512_set1_epi16(5243)), 3);
  const __m512i rest = _mm512_sub_epi16(groups, _mm512_mullo_epi16(hundreds, _mm512_set1_epi16(100)));
  const __m512i high_pairs = pair_text(hundreds), low_pairs = pair_text(rest);
  // 128-bit lane j: numbers 2j and 2j+1; unpacking puts each group's two pairs together.
  const __m512i even = _mm512_unpacklo_epi16(high_pairs, low_pairs), odd = _mm512_unpackhi_epi16(high_pairs, low_pairs);
  _mm512_store_si512(out[0], _mm512_permutex2var_epi64(even, _mm512_setr_epi64(0, 1, 8, 9, 2, 3, 10, 11), odd));
  _mm512_store_si512(out[4], _mm512_permutex2var_epi64(even, _mm512_setr_epi64(4, 5, 12, 13, 6, 7, 14, 15), odd));
}

// chunk_digits_portable, eight values at a time: the same decimals (the same window
// around ties sends the same values to std::to_chars), the same digits.
KINEMA_AVX512 void chunk_digits_avx512(const double* values, std::size_t n, int digits, ChunkDigits& chunk) {
  const double* powers = powers_of_ten().data();
  const __m512d low = _mm512_set1_pd(powers[kPowers + digits - 1]), high = _mm512_set1_pd(powers[kPowers + digits]);
  const __m512d tie_window = _mm512_set1_pd(powers[kPowers + digits] * 1e-15);
  const __m512i index_base = _mm512_set1_epi64(kPowers + digits - 1);
  const int window = kPowers + digits - 1 - 11;  // the power for exponent 11, then up to exponent -4
  const __m512i window_base = _mm512_set1_epi64(window);
  const __m512d window_low = _mm512_loadu_pd(powers + window), window_high = _mm512_loadu_pd(powers + window + 8);
  const __m512i one = _mm512_set1_epi64(1);
  for (std::size_t k = 0; k < n; k += 8) {
    const __mmask8 present = n - k >= 8 ? 0xff : static_cast<__mmask8>((1u << (n - k)) - 1);
    const __m512d value = _mm512_maskz_loadu_pd(present, values + k);
    const __m512i bits = _mm512_castpd_si512(value);
    const __m512d magnitude = _mm512_castsi512_pd(_mm512_and_si512(bits, _mm512_set1_epi64(0x7fffffffffffffffLL)));
    const __mmask8 finite_in_range = _mm512_cmp_pd_mask(magnitude, _mm512_set1_pd(1e-280), _CMP_GE_OQ) &
                                     _mm512_cmp_pd_mask(magnitude, _mm512_set1_pd(1e280), _CMP_LE_OQ) & present;
    const __m512i binary_exponent =
        _mm512_sub_epi64(_mm512_srli_epi64(_mm512_castpd_si512(magnitude), 52), _mm512_set1_epi64(1023));
    __m512i exponent = _mm512_srai_epi64(_mm512_mullo_epi64(binary_exponent, _mm512_set1_epi64(78913)), 18);
    // 10^(digits - 1 - exponent) from the 16 powers held in two registers (exponents -4
    // to 11: the magnitudes of a mechanism's results); a gather only for lanes outside them.
    const __m512i index = _mm512_sub_epi64(index_base, exponent), offset = _mm512_sub_epi64(index, window_base);
    __m512d power = _mm512_permutex2var_pd(window_low, offset, window_high);
    const __mmask8 outside = _mm512_cmp_epu64_mask(offset, _mm512_set1_epi64(15), _MM_CMPINT_GT) & finite_in_range;
    if (outside) power = _mm512_mask_i64gather_pd(power, outside, index, powers, 8);
    __m512d scaled = _mm512_mul_pd(magnitude, power);
    const __mmask8 above = _mm512_cmp_pd_mask(scaled, high, _CMP_GE_OQ) & finite_in_range;
    const __mmask8 below = _mm512_cmp_pd_mask(scaled, low, _CMP_LT_OQ) & finite_in_range;
    // One decade off: scaled by 10 or 0.1 (a second rounding, well inside the tie window).
    exponent = _mm512_mask_add_epi64(exponent, above, exponent, one);
    exponent = _mm512_mask_sub_epi64(exponent, below, exponent, one);
    scaled = _mm512_mask_mul_pd(scaled, above, scaled, _mm512_set1_pd(0.1));
    scaled = _mm512_mask_mul_pd(scaled, below, scaled, _mm512_set1_pd(10.0));
    __m512d mantissa = _mm512_roundscale_pd(scaled, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
    const __m512d fraction = _mm512_sub_pd(scaled, mantissa);
    const __m512d from_tie = _mm512_sub_pd(fraction, _mm512_set1_pd(0.5));
    const __mmask8 near_tie =
        _mm512_cmp_pd_mask(_mm512_abs_pd(from_tie), tie_window, _CMP_LT_OQ) & finite_in_range;
    mantissa = _mm512_mask_add_pd(mantissa, _mm512_cmp_pd_mask(fraction, _mm512_set1_pd(0.5), _CMP_GT_OQ), mantissa,
                                  _mm512_set1_pd(1.0));
    const __mmask8 rounded_up_a_decade = _mm512_cmp_pd_mask(mantissa, high, _CMP_GE_OQ);  // 9.99...95 -> 10.0...
    mantissa = _mm512_mask_mov_pd(mantissa, rounded_up_a_decade, low);
    exponent = _mm512_mask_add_epi64(exponent, rounded_up_a_decade, exponent, one);
    const __mmask8 number = finite_in_range & ~near_tie;
    sixteen_digits(_mm512_maskz_mov_pd(number, mantissa), chunk.texts + k);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(chunk.exponents + k), _mm512_cvtepi64_epi32(exponent));
    __m128i kinds = _mm_set1_epi8(kExact);
    kinds = _mm_mask_mov_epi8(kinds, _mm512_cmp_pd_mask(value, _mm512_setzero_pd(), _CMP_EQ_OQ), _mm_set1_epi8(kZero));
    kinds = _mm_mask_mov_epi8(kinds, _mm512_cmp_pd_mask(value, value, _CMP_UNORD_Q), _mm_set1_epi8(kEmpty));
    kinds = _mm_mask_mov_epi8(kinds, number, _mm_set1_epi8(kNumber));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(chunk.kinds + k), kinds);
  }
}

bool has_avx512() {
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                          __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
  return has;
}

bool has_avx512_vbmi() {
  static const bool has = has_avx512() && __builtin_cpu_supports("avx512vbmi");
  return has;
}

// The texts of %g's plain notation (exponent -4 to 12), each one byte shuffle of the
// significant digits (bytes 0-15) and '.', '0' (bytes 16, 17): pattern e + 4 is
// "ddd.ddd" with the point after e + 1 digits, or "0.000ddd" for a negative e. A text is
// cut to its length afterwards, so bytes past it (a point after the last kept digit,
// digits past the significant ones) do not matter; branches on the exponent, which
// changes from column to column, took a third of put_digits' time.
constexpr int kPlainLowest = -4, kPlainPatterns = 17;
struct PlainPatterns {
  alignas(32) unsigned char index[kPlainPatterns][32];
};
constexpr PlainPatterns make_plain_patterns() {
  PlainPatterns patterns{};
  for (int e = kPlainLowest; e < kPlainLowest + kPlainPatterns; ++e) {
    const int zeros = e >= 0 ? 0 : -e, point = e >= 0 ? e + 1 : 1;  // zeros: "0" and those after the point
    for (int at = 0; at < 32; ++at) {
      const int without_point = at - (at > point ? 1 : 0);
      patterns.index[e - kPlainLowest][at] = static_cast<unsigned char>(at == point              ? 16
                                                                       : without_point < zeros ? 17
                                                                                               : without_point - zeros);
    }
  }
  return patterns;
}
constexpr PlainPatterns kPlainPatternTable = make_plain_patterns();

#define KINEMA_AVX512_VBMI __attribute__((target("avx512f,avx512bw,avx512vl,avx512vbmi")))

// SignificantChunk::put with the plain notation by shuffles (32 bytes stored, the
// text's length kept); the rest as put_digits writes it.
KINEMA_AVX512_VBMI char* put_chunk_vbmi(char* out, const ChunkDigits& chunk, const double* values, std::size_t first,
                                        std::size_t last, int digits, char separator) {
  const __m128i zero_digit = _mm_set1_epi8('0');
  const __m128i point_and_zero = _mm_setr_epi8('.', '0', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0);
  const unsigned significant_mask = (1u << digits) - 1;
  for (std::size_t k = first; k < last; ++k) {
    if (k > first) *out++ = separator;
    const int exponent = chunk.exponents[k];
    if (chunk.kinds[k] == kNumber && exponent >= kPlainLowest && exponent < digits) {
      *out = '-';  // kept for a negative value only
      out += std::signbit(values[k]);
      // The significant digits first; the 16 bytes read run into the next row (there is one).
      const __m128i text = _mm_loadu_si128(reinterpret_cast<const __m128i*>(chunk.texts[k] + 16 - digits));
      // Digits kept: up to the last that is not '0' (the first never is).
      const unsigned nonzero = _mm_cmpneq_epi8_mask(text, zero_digit) & significant_mask;
      const int kept = 32 - __builtin_clz(nonzero);
      const __m256i source = _mm256_inserti128_si256(_mm256_castsi128_si256(text), point_and_zero, 1);
      const __m256i pattern =
          _mm256_load_si256(reinterpret_cast<const __m256i*>(kPlainPatternTable.index[exponent - kPlainLowest]));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out), _mm256_permutexvar_epi8(pattern, source));
      // "0." and the zeros after it, the digits or the whole part, a point before kept
      // digits past the whole part: without branches (the exponent is unpredictable).
      const int whole = exponent + 1, zeros = std::max(0, -exponent);
      out += std::max(kept, whole) + static_cast<int>(kept > whole) + zeros;
      continue;
    }
    out = put_entry(out, chunk, values, k, digits);
  }
  return out;
}
#pragma GCC diagnostic pop
#endif

}  // namespace

// std::to_chars: printf's %.*g digits without its locale and format parsing; for up to
// 13 digits a faster path that gives the same characters (checked against to_chars
// in tests/engine/analysis/number_format_test.cpp) and defers to it near a tie.
char* put_significant(char* out, double value, int significant) {
  if (value == 0) {  // no "-0"
    *out = '0';
    return out + 1;
  }
  if (SignificantChunk::handles(significant) && std::isfinite(value)) {
    char* digits = out;
    if (value < 0) *digits++ = '-';
    if (char* end = put_significant_fast(digits, std::fabs(value), significant)) return end;
  }
  return std::to_chars(out, out + kMaxNumberChars, value, std::chars_format::general, significant).ptr;
}

void SignificantChunk::convert(const double* values, std::size_t count, int significant, bool vector) {
  values_ = values;
  significant_ = significant;
  shuffled_texts_ = false;
#ifdef KINEMA_VECTOR_NUMBERS
  if (vector) {
    shuffled_texts_ = has_avx512_vbmi();
    return chunk_digits_avx512(values, count, significant, digits_);
  }
#endif
  (void)vector;
  chunk_digits_portable(values, count, significant, digits_);
}

char* SignificantChunk::put(char* out, std::size_t first, std::size_t last, char separator) const {
#ifdef KINEMA_VECTOR_NUMBERS
  if (shuffled_texts_) return put_chunk_vbmi(out, digits_, values_, first, last, significant_, separator);
#endif
  for (std::size_t k = first; k < last; ++k) {
    if (k > first) *out++ = separator;
    out = put_entry(out, digits_, values_, k, significant_);
  }
  return out;
}

char* put_significant_list(char* out, const double* values, std::size_t count, int significant, char separator) {
  if (!SignificantChunk::handles(significant)) {
    for (std::size_t k = 0; k < count; ++k) {
      if (k > 0) *out++ = separator;
      if (!std::isnan(values[k])) out = put_significant(out, values[k], significant);
    }
    return out;
  }
  SignificantChunk chunk;
  for (std::size_t begin = 0; begin < count; begin += kChunk) {
    const std::size_t n = std::min(kChunk, count - begin);
    chunk.convert(values + begin, n, significant);
    if (begin > 0) *out++ = separator;
    out = chunk.put(out, 0, n, separator);
  }
  return out;
}

bool vector_number_path() {
#ifdef KINEMA_VECTOR_NUMBERS
  return has_avx512();
#else
  return false;
#endif
}

char* put_shortest(char* out, double value) {
  return std::to_chars(out, out + kMaxNumberChars, value == 0 ? 0.0 : value).ptr;
}

std::string format_significant(double value, int significant) {
  char buffer[kMaxNumberChars];
  return std::string(buffer, put_significant(buffer, value, significant));
}

double zero_at_scale(double value, double scale) {
  return std::fabs(value) < kRoundOffFraction * scale ? 0.0 : value;
}

std::string format_at_scale(double value, double scale, int significant) {
  return format_significant(zero_at_scale(value, scale), significant);
}

double largest_magnitude(const double* values, std::size_t count) {
  double largest = 0;
  for (std::size_t k = 0; k < count; ++k)
    if (std::isfinite(values[k])) largest = std::max(largest, std::fabs(values[k]));
  return largest;
}

double largest_magnitude(std::initializer_list<double> values) { return largest_magnitude(values.begin(), values.size()); }

double round_significant(double value, int significant) {
  char buffer[64];
  const auto end =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, significant).ptr;
  double rounded = value;
  std::from_chars(buffer, end, rounded);
  return rounded;
}

std::string format_round_trip(double value) { return format_significant(value, 17); }

std::string format_fixed(double value, int decimals) {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  // A value that rounds to zero is 0, not "-0.000" (rounding noise of a coordinate).
  if (buffer[0] == '-' && std::strspn(buffer + 1, "0.") == std::strlen(buffer + 1)) return buffer + 1;
  return buffer;
}

}  // namespace kinema
