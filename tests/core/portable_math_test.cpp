// core/portable_math.h: close to libm (a few units in the last place) and the same bits on
// every machine (a digest over fixed arguments, pinned; libm's own results differ by CPU).
#include "core/portable_math.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

namespace {

using namespace shadowcert;

// |a - b| in units of the last place of b (b != 0), or in units of 2^-1074 ... near 0 the
// absolute error in units of 2^-53 is used instead (sin near its zeros).
double ulps(double a, double b) {
  const double unit = std::ldexp(1.0, std::ilogb(std::fmax(std::fabs(b), 0x1p-1021)) - 52);
  return std::fabs(a - b) / unit;
}

TEST(PortableMath, SinCosTan_WithinFewUlpsOfLibm) {
  double worst_sin = 0, worst_cos = 0, worst_tan = 0;
  for (int i = -200000; i <= 200000; ++i) {
    const double x = i * 7.3e-4;  // [-146, 146]: every quadrant many times
    // Near a zero the value's own ulp is tiny: compare against the argument's scale there.
    const double s = std::sin(x), c = std::cos(x);
    worst_sin = std::fmax(worst_sin, std::fabs(s) < 1e-3 ? std::fabs(portable::sin(x) - s) / 0x1p-53 : ulps(portable::sin(x), s));
    worst_cos = std::fmax(worst_cos, std::fabs(c) < 1e-3 ? std::fabs(portable::cos(x) - c) / 0x1p-53 : ulps(portable::cos(x), c));
    if (std::fabs(c) > 1e-3 && std::fabs(s) > 1e-3) worst_tan = std::fmax(worst_tan, ulps(portable::tan(x), std::tan(x)));
  }
  EXPECT_LE(worst_sin, 2.0);
  EXPECT_LE(worst_cos, 2.0);
  EXPECT_LE(worst_tan, 4.0);
  EXPECT_EQ(portable::sin(0.0), 0.0);
  EXPECT_EQ(portable::cos(0.0), 1.0);
  EXPECT_EQ(portable::tan(0.0), 0.0);
  // Not finite: NaN as libm (and no undefined float-to-integer cast for UBSan to report).
  EXPECT_TRUE(std::isnan(portable::sin(HUGE_VAL)));
  EXPECT_TRUE(std::isnan(portable::cos(-HUGE_VAL)));
  EXPECT_TRUE(std::isnan(portable::tan(NAN)));
  EXPECT_TRUE(std::isnan(portable::exp(NAN)));
  EXPECT_EQ(portable::exp(-HUGE_VAL), 0.0);
  EXPECT_EQ(portable::exp(HUGE_VAL), HUGE_VAL);
  // Large arguments: reduced by fmod first, still the right value to a few 1e-13.
  EXPECT_NEAR(portable::sin(1e7), std::sin(1e7), 1e-8);
}

TEST(PortableMath, ExpLogPow_WithinFewUlpsOfLibm) {
  double worst_exp = 0, worst_log = 0, worst_log2 = 0, worst_log10 = 0, worst_cbrt = 0;
  for (int i = -70000; i <= 70000; ++i) {
    const double x = i * 1.01e-2;  // [-707, 707]
    worst_exp = std::fmax(worst_exp, ulps(portable::exp(x), std::exp(x)));
    const double y = std::exp(x * 0.9);  // (0, inf): every binade from 1e-276 to 1e276
    worst_log = std::fmax(worst_log, std::fabs(portable::log(y) - std::log(y)) / std::fmax(std::fabs(std::log(y)) * 0x1p-52, 0x1p-60));
    worst_log2 = std::fmax(worst_log2, std::fabs(portable::log2(y) - std::log2(y)) / std::fmax(std::fabs(std::log2(y)) * 0x1p-52, 0x1p-60));
    worst_log10 = std::fmax(worst_log10, std::fabs(portable::log10(y) - std::log10(y)) / std::fmax(std::fabs(std::log10(y)) * 0x1p-52, 0x1p-60));
    worst_cbrt = std::fmax(worst_cbrt, ulps(portable::cbrt(x), std::cbrt(x) == 0 ? 1.0 : std::cbrt(x)) * (x != 0));
  }
  // exp's error grows with |x| through x - n ln 2 (at most |n| 2^-85 of the argument).
  EXPECT_LE(worst_exp, 4.0);
  EXPECT_LE(worst_log, 4.0);
  EXPECT_LE(worst_log2, 4.0);
  EXPECT_LE(worst_log10, 4.0);
  EXPECT_LE(worst_cbrt, 4.0);
  for (int e = -1000; e <= 1000; ++e) ASSERT_EQ(portable::log2(std::ldexp(1.0, e)), e) << "log2 of 2^" << e;
  EXPECT_EQ(portable::exp(0.0), 1.0);
  EXPECT_EQ(portable::log(1.0), 0.0);
  EXPECT_EQ(portable::exp(1000.0), HUGE_VAL);
  EXPECT_EQ(portable::exp(-1000.0), 0.0);
  EXPECT_TRUE(std::isnan(portable::log(-1.0)));
  EXPECT_EQ(portable::log(0.0), -HUGE_VAL);
  EXPECT_NEAR(portable::exp10(-3.0), 1e-3, 1e-18);
  EXPECT_NEAR(portable::pow(2.0, 0.5), std::sqrt(2.0), 1e-15);
  EXPECT_EQ(portable::cbrt(-27.0), -3.0);
}

TEST(PortableMath, Hypot_NoOverflowOrUnderflow) {
  EXPECT_EQ(portable::hypot(3.0, 4.0, 12.0), 13.0);
  EXPECT_DOUBLE_EQ(portable::hypot(3e200, 4e200, 0.0), 5e200);
  EXPECT_DOUBLE_EQ(portable::hypot(3e-200, 0.0, 4e-200), 5e-200);
  EXPECT_EQ(portable::hypot(0.0, 0.0, 0.0), 0.0);
  EXPECT_EQ(portable::hypot(-2.0, 0.0, 0.0), 2.0);
}

// The same bits everywhere: a digest of every function over fixed arguments, pinned. libm's
// results for the same arguments hash differently on CPUs with and without FMA; these must not
// (only correctly rounded basic operations). A change of the functions changes this digest,
// and with it every fuzz seed's case and every pinned exact-image digest: regenerate those too.
TEST(PortableMath, FixedArguments_PinnedDigest) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  const auto add = [&h](double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    for (int k = 0; k < 8; ++k) h = (h ^ ((bits >> (8 * k)) & 0xff)) * 0x100000001b3ULL;
  };
  for (int i = -5000; i <= 5000; ++i) {
    const double x = i * 3.7e-3;
    add(portable::sin(x));
    add(portable::cos(x));
    add(portable::tan(x));
    add(portable::exp(x * 10.0));
    add(portable::exp10(x));
    add(portable::log(std::fabs(x) + 1e-3));
    add(portable::log2(std::fabs(x) + 1e-3));
    add(portable::log10(std::fabs(x) + 1e-3));
    add(portable::cbrt(x));
    add(portable::pow(std::fabs(x) + 0.5, 1.7));
    add(portable::hypot(x, 2.0 * x, 1.0));
  }
  std::ostringstream hex;
  hex << std::hex << h;
  EXPECT_EQ(hex.str(), "7aca4f59d79078aa") << "core/portable_math.h's results changed";
}

}  // namespace
