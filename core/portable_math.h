#pragma once
// Elementary functions that give the same bits on every x86-64 machine.
//
// Why: glibc's libm picks its sin, cos, tan, exp, log, pow and cbrt at run time by CPU
// (FMA/AVX2 variants where the CPU has them), and the variants differ in the last bit (on
// this project's machines: 2M arguments of sin, cos, pow(10, x), log10 and log2 each hash
// differently with GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA). Everything that
// defines an exact answer's input must not depend on that: a camera's pixel rays, a procedural
// mesh, a scene's rotations, a light orbit, a fuzz seed's soup. Otherwise a seed, a scene
// file or a pinned digest gives a different case, image or certificate on another machine
// (CI's exact-image digests did: docs/development.md#portable-math).
//
// How: only IEEE-754 basic operations (+, -, *, /, sqrt, each correctly rounded), exact
// helpers (frexp, ldexp, fmod, round, floor) and fixed polynomial evaluations, compiled with
// -ffp-contract=off (the top CMakeLists.txt) so no compiler fuses a multiply-add. The results
// are within a few units in the last place of the true values (tests/core/portable_math_test),
// not correctly rounded: what matters here is that they are the same everywhere.
//
// Arguments: any double; NaN and infinities give NaN, inf or 0 as libm does (no undefined cast). sin, cos and tan reduce |x| <= 2^20 by a three-part pi/2
// (Cody and Waite), larger |x| first by fmod with 2 pi in double (exact, so still the same
// bits everywhere, but no longer accurate to the last place). log and log2/log10 take x > 0;
// exp and pow overflow to inf and underflow to 0 as expected.
#include <cmath>
#include <cstdint>

namespace shadowcert::portable {

inline constexpr double kPi = 3.14159265358979323846;

namespace detail {

// pi/2 in three parts, the first two with 33 significant bits, so n * part is exact for
// |n| < 2^20: r = x - n pi/2 to about 2^-85 relative.
inline constexpr double kHalfPi1 = 1.57079632673412561417e+00;
inline constexpr double kHalfPi2 = 6.07710050630396597660e-11;
inline constexpr double kHalfPi3 = 2.02226624879595063154e-21;
inline constexpr double kTwoOverPi = 6.36619772367581382433e-01;

struct Quadrant {
  int n;     // x = n pi/2 + r, n mod 4 in [0, 4)
  double r;  // |r| <= about pi/4
};

inline Quadrant reduce(double x) {
  if (!std::isfinite(x)) return {0, x - x};  // NaN, as libm: no cast of a NaN to an integer below
  if (std::fabs(x) > 1048576.0) x = std::fmod(x, 2.0 * kPi);  // exact in IEEE arithmetic
  const double n = std::round(x * kTwoOverPi);
  const double r = ((x - n * kHalfPi1) - n * kHalfPi2) - n * kHalfPi3;
  const auto q = static_cast<std::int64_t>(n);
  return {static_cast<int>(((q % 4) + 4) % 4), r};
}

// Taylor series on |r| <= pi/4 + a little, Horner in r^2: the first omitted term is below
// 2^-60 of the sum.
inline double sin_kernel(double r) {
  const double z = r * r;
  // Coefficients (-1)^k / (2k+1)!, k = 1..10.
  constexpr double c[] = {-1.0 / 6.0,
                          1.0 / 120.0,
                          -1.0 / 5040.0,
                          1.0 / 362880.0,
                          -1.0 / 39916800.0,
                          1.0 / 6227020800.0,
                          -1.0 / 1307674368000.0,
                          1.0 / 355687428096000.0,
                          -1.0 / 121645100408832000.0,
                          1.0 / 51090942171709440000.0};
  double p = c[9];
  for (int k = 8; k >= 0; --k) p = p * z + c[k];
  return r + r * (z * p);
}

inline double cos_kernel(double r) {
  const double z = r * r;
  // Coefficients (-1)^k / (2k)!, k = 1..10.
  constexpr double c[] = {-1.0 / 2.0,
                          1.0 / 24.0,
                          -1.0 / 720.0,
                          1.0 / 40320.0,
                          -1.0 / 3628800.0,
                          1.0 / 479001600.0,
                          -1.0 / 87178291200.0,
                          1.0 / 20922789888000.0,
                          -1.0 / 6402373705728000.0,
                          1.0 / 2432902008176640000.0};
  double p = c[9];
  for (int k = 8; k >= 0; --k) p = p * z + c[k];
  return 1.0 + z * p;
}

inline constexpr double kLn2Hi = 6.93147180369123816490e-01;  // 32 significant bits: e * hi exact
inline constexpr double kLn2Lo = 1.90821492927058770002e-10;
inline constexpr double kInvLn2 = 1.44269504088896338700e+00;
inline constexpr double kLn10 = 2.30258509299404568402e+00;
inline constexpr double kInvLn10 = 4.34294481903251827651e-01;
inline constexpr double kSqrtHalf = 7.07106781186547524401e-01;

// log(m) for m in [sqrt(1/2), sqrt(2)): 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716.
inline double log_kernel(double m) {
  const double s = (m - 1.0) / (m + 1.0);
  const double z = s * s;
  double p = 1.0 / 23.0;
  for (int k = 21; k >= 3; k -= 2) p = p * z + 1.0 / k;
  return 2.0 * s + 2.0 * s * (z * p);
}

// x = 2^e m with m in [sqrt(1/2), sqrt(2)).
inline double split(double x, int& e) {
  double m = std::frexp(x, &e);  // m in [0.5, 1)
  if (m < kSqrtHalf) {
    m *= 2.0;
    --e;
  }
  return m;
}

}  // namespace detail

[[nodiscard]] inline double sin(double x) {
  const detail::Quadrant q = detail::reduce(x);
  switch (q.n) {
    case 0: return detail::sin_kernel(q.r);
    case 1: return detail::cos_kernel(q.r);
    case 2: return -detail::sin_kernel(q.r);
    default: return -detail::cos_kernel(q.r);
  }
}

[[nodiscard]] inline double cos(double x) {
  const detail::Quadrant q = detail::reduce(x);
  switch (q.n) {
    case 0: return detail::cos_kernel(q.r);
    case 1: return -detail::sin_kernel(q.r);
    case 2: return -detail::cos_kernel(q.r);
    default: return detail::sin_kernel(q.r);
  }
}

[[nodiscard]] inline double tan(double x) {
  const detail::Quadrant q = detail::reduce(x);
  const double s = detail::sin_kernel(q.r), c = detail::cos_kernel(q.r);
  return (q.n % 2 == 0) ? s / c : -c / s;
}

// e^x: x = n ln 2 + r with |r| <= ln(2)/2, e^r by its Taylor series, then 2^n exactly.
[[nodiscard]] inline double exp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.8) return HUGE_VAL;
  if (x < -745.2) return 0.0;
  const double n = std::round(x * detail::kInvLn2);
  const double r = (x - n * detail::kLn2Hi) - n * detail::kLn2Lo;
  // e^r = 1 + r (1 + r/2! + ... + r^12/13!): the first omitted term is below 2^-60.
  constexpr double c[] = {1.0,           1.0 / 2.0,          1.0 / 6.0,          1.0 / 24.0,
                          1.0 / 120.0,   1.0 / 720.0,        1.0 / 5040.0,       1.0 / 40320.0,
                          1.0 / 362880.0, 1.0 / 3628800.0,   1.0 / 39916800.0,   1.0 / 479001600.0,
                          1.0 / 6227020800.0};
  double p = c[12];
  for (int k = 11; k >= 0; --k) p = p * r + c[k];
  return std::ldexp(1.0 + r * p, static_cast<int>(n));
}

// Natural logarithm of x > 0 (NaN for x < 0, -inf for 0).
[[nodiscard]] inline double log(double x) {
  if (!(x > 0.0)) return x == 0.0 ? -HUGE_VAL : NAN;
  if (std::isinf(x)) return x;
  int e = 0;
  const double m = detail::split(x, e);
  return e * detail::kLn2Hi + (e * detail::kLn2Lo + detail::log_kernel(m));
}

// log2 and log10: exact at powers of two (log2) since the kernel is 0 at m == 1.
[[nodiscard]] inline double log2(double x) {
  if (!(x > 0.0) || std::isinf(x)) return log(x);
  int e = 0;
  const double m = detail::split(x, e);
  return e + detail::log_kernel(m) * detail::kInvLn2;
}

[[nodiscard]] inline double log10(double x) { return log(x) * detail::kInvLn10; }

// x^y for x > 0 as e^(y log x): deterministic, a few ulp times |y log x| from the true value.
[[nodiscard]] inline double pow(double x, double y) {
  if (y == 0.0) return 1.0;
  if (x == 1.0) return 1.0;
  return exp(y * log(x));
}

// 10^y with the product y ln 10 in one rounding.
[[nodiscard]] inline double exp10(double y) { return exp(y * detail::kLn10); }

// Cube root: a start from exp(log|x| / 3), then two Newton steps.
[[nodiscard]] inline double cbrt(double x) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  const double a = std::fabs(x);
  double y = exp(log(a) / 3.0);
  for (int k = 0; k < 2; ++k) y = y - (y * y * y - a) / (3.0 * y * y);
  return x < 0.0 ? -y : y;
}

// sqrt(x^2 + y^2 + z^2) without overflow or underflow in the squares: each term scaled by the
// largest magnitude (a power of two near it, so the scaling is exact).
[[nodiscard]] inline double hypot(double x, double y, double z) {
  const double big = std::fmax(std::fabs(x), std::fmax(std::fabs(y), std::fabs(z)));
  if (big == 0.0 || !std::isfinite(big)) return big;
  int e = 0;
  (void)std::frexp(big, &e);
  const double sx = std::ldexp(x, -e), sy = std::ldexp(y, -e), sz = std::ldexp(z, -e);
  return std::ldexp(std::sqrt(sx * sx + sy * sy + sz * sz), e);
}

}  // namespace shadowcert::portable
