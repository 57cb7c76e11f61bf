// sin and cos together, written so that a loop over lanes vectorises (no
// branches, no calls): Cody-Waite reduction by pi/2 and fdlibm's kernel
// polynomials, within about 1 ulp of libm for |x| < 1.6e6; larger or non-finite
// arguments go to libm. glibc's sin/cos are scalar calls, and Eigen 3.4 does not
// vectorise double sin/cos, so the batch tape needs its own. The scalar tape
// uses the same formulas, so both paths agree to rounding (the AVX2 build may
// fuse multiply-adds).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

// Functions made of loops over lanes are compiled twice, for x86-64-v3 (AVX2)
// and for any x86-64, and the loader picks the one the processor runs.
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define KINEMA_LANE_LOOPS __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define KINEMA_LANE_LOOPS
#endif

namespace kinema::simd {

/// Largest |x| reduced here: j = round(x 2/pi) < 2^20 keeps j * kPio2High exact.
constexpr double kSinCosLimit = 1.6e6;

/// Both values for one argument, |x| <= kSinCosLimit (else the result is meaningless).
inline void sincos_reduced(double x, double& sin_x, double& cos_x) {
  // pi/2 in three 33-bit pieces (fdlibm's pio2_1, pio2_2, pio2_3).
  constexpr double kPio2High = 1.57079632673412561417e+00;
  constexpr double kPio2Mid = 6.07710050630396597660e-11;
  constexpr double kPio2Low = 2.02226624871116645580e-21;
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kRound = 0x1.8p52;  // adding it rounds to an integer in the low bits
  const double shifted = x * kTwoOverPi + kRound;
  const double j = shifted - kRound;
  std::uint64_t bits;
  std::memcpy(&bits, &shifted, sizeof bits);
  const std::uint64_t quadrant = bits & 3u;
  const double r = ((x - j * kPio2High) - j * kPio2Mid) - j * kPio2Low;

  const double z = r * r;
  // fdlibm __kernel_sin and __kernel_cos on [-pi/4, pi/4].
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double sin_r = r + (z * r) * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
  const double cos_tail = z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
  const double half_z = 0.5 * z;
  const double w = 1.0 - half_z;
  const double cos_r = w + (((1.0 - w) - half_z) + cos_tail);

  // Quadrant: odd ones swap sin and cos; the sign bits follow the quadrant.
  const bool odd = (quadrant & 1u) != 0;
  double s = odd ? cos_r : sin_r;
  double c = odd ? sin_r : cos_r;
  std::uint64_t s_bits, c_bits;
  std::memcpy(&s_bits, &s, sizeof s_bits);
  std::memcpy(&c_bits, &c, sizeof c_bits);
  s_bits ^= (quadrant & 2u) << 62;
  c_bits ^= ((quadrant + 1u) & 2u) << 62;
  std::memcpy(&s, &s_bits, sizeof s);
  std::memcpy(&c, &c_bits, sizeof c);
  sin_x = s;
  cos_x = c;
}

/// Scalar sin and cos with the batch arithmetic.
inline void sincos(double x, double& sin_x, double& cos_x) {
  if (std::fabs(x) <= kSinCosLimit) {
    sincos_reduced(x, sin_x, cos_x);
  } else {
    sin_x = std::sin(x);
    cos_x = std::cos(x);
  }
}

}  // namespace kinema::simd
